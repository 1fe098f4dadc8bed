"""Fixtures shared by the lmp test suites."""
import pytest

from granmn_run import run_lammps
from pile_decks import PILE, styles


@pytest.fixture(scope="module")
def settled(tmp_path_factory):
    """The pile settled on the floor under vertical gravity: the common start of every
    variant, which then tilts gravity so that the pile starts to move with its contacts on."""
    run = run_lammps(PILE + styles(0.5, tilt=0.0) + "run 150000\nwrite_data settled.data\n",
                     tmp_path_factory.mktemp("settle"))
    return run.workdir / "settled.data"
