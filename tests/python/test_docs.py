"""docs/bad_input.md lists every bad input the tests try."""
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests" / "lammps"))

import test_bad_input  # noqa: E402
import test_counters  # noqa: E402
import test_scenes  # noqa: E402
import test_sweep  # noqa: E402

DOC = (ROOT / "docs" / "bad_input.md").read_text()


def test_every_bad_input_case_is_in_the_table():
    tables = [test_bad_input.ERRORS, test_counters.BAD, test_scenes.BAD_VARIABLES,
              test_scenes.BAD_FRICTIONAL_VARIABLES, test_sweep.BAD_CONFIGS]
    for table in tables:
        for case, (_, message) in table.items():
            assert f"| {case}" in DOC and message.replace("|", "\\|") in DOC, case
