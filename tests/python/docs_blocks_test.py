"""The ```python blocks of a Markdown page run, in order, in one namespace, from the repository's
root: a tutorial page whose code stays true. Usage: docs_blocks_test.py PAGE.md"""
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))


def main():
    page = sys.argv[1]
    blocks = re.findall(r"^```python\n(.*?)^```", open(page).read(), re.S | re.M)
    if not blocks:
        sys.exit(f"{page}: no python block")
    os.chdir(ROOT)
    namespace = {"__name__": "__docs__"}
    for k, block in enumerate(blocks, 1):
        print(f"--- block {k} of {len(blocks)}")
        exec(compile(block, f"{page}, block {k}", "exec"), namespace)
    print(f"{len(blocks)} blocks of {page} ran")


if __name__ == "__main__":
    main()
