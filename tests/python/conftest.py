# Shared by the tests of the Python module: the repository's paths, and the `mbgen` command when CTest names it
# (MBGEN_COMMAND) for the tests that compare the module with the command.
import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
MDOF2 = ROOT / "examples" / "mdof2"


@pytest.fixture
def mbgen_command():
    command = os.environ.get("MBGEN_COMMAND") or shutil.which("mbgen")
    if not command:
        pytest.skip("the mbgen command is not known (CTest sets MBGEN_COMMAND)")
    return command
