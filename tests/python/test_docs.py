"""docs/bad_input.md lists every bad input the tests try."""
from pathlib import Path

import test_bad_input
import test_checkpoint
import test_chute_3d
import test_counters
import test_nve_disc_mn
import test_scenes
import test_sweep

ROOT = Path(__file__).resolve().parents[2]

DOC = (ROOT / "docs" / "bad_input.md").read_text()


def test_every_bad_input_case_is_in_the_table():
    tables = [test_bad_input.ERRORS, test_counters.BAD, test_nve_disc_mn.BAD, test_scenes.BAD_VARIABLES,
              test_scenes.BAD_FRICTIONAL_VARIABLES, test_scenes.BAD_SINGLE_DISK_VARIABLES,
              test_sweep.BAD_CONFIGS, test_sweep.BAD_OUTPUTS, test_chute_3d.BAD_3D,
              test_checkpoint.BAD_WINDOWS]
    for table in tables:
        for case, (_, message) in table.items():
            assert f"| {case}" in DOC and message.replace("|", "\\|") in DOC, case
