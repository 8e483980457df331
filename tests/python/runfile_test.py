"""sffcal.runfile's pure-Python reader (h5py): a committed schema-1 reference run (its friction
from the stored config), the analysis tables, the CSV reader on a table with a comment, a text
column and empty cells, the end window, and RunFileError naming what is missing. Run by CTest with
pytest (PYTHONPATH=BUILD/python)."""
import os

import numpy as np
import pytest

from sffcal import runfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
REFERENCE = os.path.join(ROOT, "tests", "data", "reference", "matrix", "iso_dense_100kPa.h5")


def test_a_schema_1_reference_run_reads_with_the_cpp_names():
    assert runfile.name_of(REFERENCE) == "iso_dense_100kPa"
    with runfile.open_run(REFERENCE) as f:
        assert runfile.friction(f) == pytest.approx(np.tan(np.radians(30)), rel=1e-15)
        assert runfile.loading_path(f) == "drained_compression"
        series = runfile.series(f, ["axial_strain", "p"])
        assert set(series) == {"axial_strain", "p"}
        assert np.all(np.diff(series["axial_strain"]) > 0) and np.all(series["p"] > 0)
        sff = runfile.table(f, "sff", ["a_c", "axial_strain"])
        assert len(sff["a_c"]) == len(sff["axial_strain"]) > 1
        with pytest.raises(runfile.RunFileError, match="no_such_column"):
            runfile.series(f, ["no_such_column"])
        with pytest.raises(runfile.RunFileError, match="sffcal sff"):
            runfile.table(f, "no_such_table")


def test_the_csv_reader_keeps_text_columns_and_reads_empty_cells_as_nan(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text("# a comment line\nstep,q,status\n0,1.5,ok\n1,,unreliable\n")
    table = runfile.read_csv_table(str(path))
    assert table["status"] == ["ok", "unreliable"]
    assert table["q"][0] == 1.5 and np.isnan(table["q"][1])
    assert runfile.read_csv_rows(str(path))[0] == ["step", "q", "status"]


def test_the_end_window_is_the_last_width_of_axial_strain_in_either_direction():
    strain = np.linspace(0.0, 0.3, 31)
    assert np.array_equal(runfile.end_window(strain), strain >= 0.25 - 1e-12)
    assert np.array_equal(runfile.end_window(-strain), strain >= 0.25 - 1e-12)


def test_a_file_that_is_not_hdf5_is_named(tmp_path):
    path = tmp_path / "not.h5"
    path.write_text("text")
    with pytest.raises(runfile.RunFileError, match="not.h5"):
        runfile.open_run(str(path))
