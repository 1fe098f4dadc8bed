"""The per-step fast paths leave the trajectory alone: a scene gives bitwise the same
final state with the counters off (fix contacts/mn is passive) and with the fix enforce2d the
decks no longer define (it zeroed what was already zero). The counters' own serial path (a
ghost's tallies added to the disk it images) is checked against the reverse-communication path
by test_counters.py (newton off, 2 ranks)."""
import shutil

import numpy as np
import pytest

from granmn_run import INPUTS, PLUGIN, run_lammps, run_scene

# Long enough for the disks to land: the flows have disk-disk and boundary contacts by then.
RUN = dict(run_time=6, average_start=3, stop_energy=0)


def final_state(tmp_path, scene, lib=INPUTS / "lib", **variables):
    """The scene deck, then every disk's position, velocity and spin to the last bit."""
    settings = dict(RUN, plugin=PLUGIN, lib=lib, out=tmp_path, **variables)
    deck = "".join(f'variable {name} index "{value}"\n' for name, value in settings.items())
    deck += (f"include {INPUTS / (scene + '.lmp')}\n"
             "write_dump all custom final.txt id x y vx vy omegaz modify sort id "
             "format float %.17g\n")
    run = run_lammps(deck, tmp_path, header=False)
    return run, (tmp_path / "final.txt").read_text().splitlines()[9:]


def lib_with_enforce2d(tmp_path):
    lib = tmp_path / "lib"
    shutil.copytree(INPUTS / "lib", lib)
    with open(lib / "dynamics.lmp", "a") as f:
        f.write("fix flat all enforce2d\n")
    return lib


@pytest.mark.parametrize("scene", ["frictional_flow", "collisional_flow"])
def test_counters_and_enforce2d_leave_the_trajectory_bitwise_alone(tmp_path, scene):
    run, reference = final_state(tmp_path / "default", scene)
    begun = run.table("energy.txt")[:, 4:6].sum(axis=1)    # with disks and the boundary
    assert begun.max() > 10, "few contacts: the comparison would show little"
    off, without_counters = final_state(tmp_path / "no_counters", scene, counters="no")
    _, with_enforce2d = final_state(tmp_path / "enforce2d", scene,
                                    lib=lib_with_enforce2d(tmp_path))
    assert len(reference) == 100
    assert without_counters == reference
    assert with_enforce2d == reference
    # energy.txt's header names the columns it has (the post-processing reads them by name)
    for r in (run, off):
        lines = (r.workdir / "energy.txt").read_text().splitlines()
        assert len(lines[1].split()) - 1 == len(lines[2].split()), lines[1:3]
    positions = np.loadtxt(reference)[:, 1:3]
    assert np.all(np.isfinite(positions))


@pytest.mark.parametrize("variables,message", [
    (dict(counters="maybe"), "deck variable counters = maybe must be yes or no"),
    (dict(counters="no", rows="yes"), "rows = yes needs counters = yes"),
])
def test_bad_counters_variable_stops_with_a_message(tmp_path, variables, message):
    run = run_scene("frictional_flow", tmp_path, check=False, **variables)
    assert run.returncode != 0 and message in run.output, run.output[-1500:]
