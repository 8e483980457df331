"""What the CalculiX example scripts share (single_element.py, rotated_element.py): their
common options, a new output folder, and the UMAT's cards from `sffcal umat-cards`."""
import os
import re
import subprocess
import sys


def add_common_arguments(parser):
    """--ccx, --sffcal, --parameters, --dem and -o."""
    parser.add_argument("--ccx", required=True, help="ccx with sffcal's UMAT (build_calculix.sh)")
    parser.add_argument("--sffcal", required=True)
    parser.add_argument("--parameters", required=True, help="parameter file of any registered model")
    parser.add_argument("--dem", help="start from this DEM run (else a plain specimen)")
    parser.add_argument("-o", "--output", required=True, help="folder (created; must be new)")


def new_folder(path, script):
    """Creates `path` and returns it absolute; exits naming `script` where it exists."""
    if os.path.exists(path):
        sys.exit(f"{script}: {path} exists; give a new folder")
    os.makedirs(path)
    return os.path.abspath(path)


def umat_cards(sffcal, parameters, start, elements="1"):
    """The cards of the elements `elements` (`sffcal umat-cards ... --elements 1-27`) from the
    start options `start`, and the material's name in them."""
    cards = subprocess.run([sffcal, "umat-cards", "--parameters", parameters, *start,
                            "--elements", elements], check=True, capture_output=True,
                           text=True).stdout
    return cards, re.search(r"\*MATERIAL, NAME=(\S+)", cards).group(1)
