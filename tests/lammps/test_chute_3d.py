"""inputs/chute_3d.lmp, the 3D chute (docs/scenes.md): a small chute runs in 3D, its
outputs are read by the post-processing (N_c, N_w, t_c, t_w per sphere per unit time), its
kinetic energies are those of solid spheres, and refused variables stop it with a message;
the sweep runner's preset is known and within its budget; two MPI ranks give the one-rank run's
counts and contacts, and a killed run resumed from its checkpoint, on the same or another
number of ranks, those of the uninterrupted run."""
import collections
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from granmn_run import BUILD_PATHS, ROOT, SERIAL, SERIAL_REASON, energy_of, run_scene

from postprocess.io import ENERGY_COLUMNS, read_counts, read_profile, read_rows
from postprocess.observables import point_observables

# dt = dt_cap = 1e-3 (tau_c/16): the snapshots (every 6000 steps) fall on lines of energy.txt
# (every 100)
SMALL = dict(kn=2e4, dt_fraction=0.1, dt_cap=1e-3, spheres=60, length=5, width=5,
             sin_theta=0.40, run_time=12, average_start=6, snapshot_interval=6)


def last_frame(path):
    """The last frame of a LAMMPS text dump as {column: array}."""
    frame = path.read_text().split("ITEM: TIMESTEP")[-1].splitlines()
    start = next(i for i, line in enumerate(frame) if line.startswith("ITEM: ATOMS"))
    data = np.loadtxt(frame[start + 1:], ndmin=2)
    return int(frame[1]), {name: data[:, k] for k, name in enumerate(frame[start].split()[2:])}


def test_small_chute_runs_in_3d_and_the_pipeline_reads_it(tmp_path):
    run = run_scene("chute_3d", tmp_path, **SMALL)
    params = dict(line.split() for line in (tmp_path / "params.txt").read_text().splitlines())
    assert params["scene"] == "chute_3d" and params["dimension"] == "3"
    assert int(params["n_mobile"]) == 60
    assert "3D: solid spheres, q = 7/2" in run.output

    # the energies of the last line are those of the last snapshot's solid spheres
    # (mass d^3, I = 2 m r^2/5), per flowing sphere
    step, atoms = last_frame(tmp_path / "snapshots.lammpstrj")
    energy = run.table("energy.txt")
    assert step == 12000
    line = energy[energy[:, 0] == step][0]
    mobile = atoms["type"] == 1
    mass = (2 * atoms["radius"][mobile]) ** 3
    v2 = sum(atoms[c][mobile] ** 2 for c in ("vx", "vy", "vz"))
    w2 = sum(atoms[c][mobile] ** 2 for c in ("omegax", "omegay", "omegaz"))
    e_trans = 0.5 * mass @ v2 / 60
    e_rot = 0.5 * 0.4 * (mass * atoms["radius"][mobile] ** 2) @ w2 / 60
    # (the dump prints 6 digits; a disc inertia would be 25 % off)
    assert line[1] == pytest.approx(e_trans, rel=1e-4)
    assert line[2] == pytest.approx(e_rot, rel=1e-4)
    # sensible: it moves, it has not blown up, no sphere fell through the base (heights
    # 0.5 - 1.0, base_rough 0.5) and the fixed spheres did not move
    assert np.all(np.isfinite(energy[:, 1:4])) and 0.01 < line[3] < 10
    assert atoms["z"][mobile].min() > 0.9
    base = atoms["type"] == 2
    assert base.sum() == 25 and np.all(atoms["vx"][base] == 0) and np.all(atoms["vz"][base] == 0)
    assert atoms["z"][base].min() >= 0.5 and atoms["z"][base].max() < 1.0

    counts = run.atoms("counts.txt")
    assert len(counts["id"]) == 60
    assert 0.9 <= counts["diameter"].min() and counts["diameter"].max() <= 1.1
    assert counts["f_c[1]"].sum() > 0 and counts["f_c[2]"].sum() > 0

    # the post-processing: per flowing sphere per unit time, N_w per sphere that touched
    # the base; a profile binned along z
    o = point_observables(tmp_path)
    assert o["scene"] == "chute_3d" and 0 < o["n_boundary"] <= 60
    for name in ("N_c", "N_w", "t_c", "t_w"):
        assert np.isfinite(o[name]) and o[name] > 0, (name, o[name])
    assert o["t_c"] <= 1 and o["t_w"] <= 1
    assert o["E_total"] == pytest.approx(energy[energy[:, 0] * float(params["dt"]) >= 6, 3]
                                         .mean(), rel=0.05)
    profile = [l.split() for l in (tmp_path / "profile.txt").read_text().splitlines()
               if l.strip() and not l.startswith("#")][1:]
    assert max(float(p[1]) for p in profile) > 1.5       # bins of height z above the base


BAD_3D = {
    "fused integration": (dict(integration="fused"),
                          "in 3D only integration = separate with integrator = verlet"),
    "ab2": (dict(integrator="ab2"), "in 3D only integration = separate with integrator = verlet"),
    "no spheres": (dict(spheres=0), "deck variable spheres = 0 must be a positive integer"),
    "narrow base": (dict(width=2), "must be integers >= 3"),
    "base too rough": (dict(base_rough=0.8), "base_rough = 0.8 must lie in [0, 0.5]"),
}


@pytest.mark.parametrize("scene, dimension", [("frictional_flow", 3), ("single_disk", 3)])
def test_a_dimension_other_than_the_scenes_is_refused(tmp_path, scene, dimension):
    """A 2D scene's geometry in a 3D box would run, wrongly: the decks refuse it."""
    run = run_scene(scene, tmp_path, check=False, dimension=dimension)
    assert run.returncode != 0, run.output[-1500:]
    assert (f"inputs/{scene}.lmp is a 2D scene: -var dimension {dimension} does not apply"
            in run.output), run.output[-1500:]


@pytest.mark.parametrize("case", sorted(BAD_3D))
def test_bad_chute_variables_stop_with_a_message(tmp_path, case):
    variables, message = BAD_3D[case]
    run = run_scene("chute_3d", tmp_path, check=False, **{**SMALL, **variables})
    assert run.returncode != 0 and message in run.output, run.output[-1500:]


def test_the_chute_preset_is_known_to_the_runner_and_within_budget(tmp_path):
    """inputs/sweeps/chute_3d.toml: every point is a chute_3d point the runner accepts; the
    predicted cost (its cost model: spheres + base atoms, the 3D per-atom cost) stays under
    the preset's budget of ~3 CPU-hours."""
    build = BUILD_PATHS.directory
    proc = subprocess.run([sys.executable, "-m", "scripts.sweep",
                           str(ROOT / "inputs" / "sweeps" / "chute_3d.toml"), "--output",
                           str(tmp_path / "out"), "--build", str(build), "--dry-run"],
                          cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    hours = float(re.search(r"\(([\d.]+) CPU-hours\)", proc.stdout).group(1))
    points = proc.stdout.count(" todo chute_3d/")
    print(proc.stdout.splitlines()[0])
    assert points >= 2 * 4 * 2 and 0.5 < hours <= 3.0


def preset_points(name):
    """The points of inputs/sweeps/<name>.toml as the runner expands them."""
    from scripts.granmn_sweep.config import expand, load_config
    path = ROOT / "inputs" / "sweeps" / f"{name}.toml"
    return expand(load_config(path), path)


def test_the_stiff_preset_goes_on_with_the_dense_series():
    """inputs/sweeps/chute_3d_stiff.toml extends chute_3d.toml's dense series: analysed
    together (postprocess report/limit with both directories) its points must be the same
    series, i.e. differ from the dense points in kn alone, at stiffer kn, with the same seeds;
    else they would be a separate series of two k_n, and the limit rule would not see them."""
    base = [p for p in preset_points("chute_3d") if p["spheres"] == 500]
    stiff = preset_points("chute_3d_stiff")
    rest = lambda p: {k: v for k, v in p.items() if k not in ("kn", "seed")}
    assert base and stiff and {repr(rest(p)) for p in base + stiff} == {repr(rest(base[0]))}
    assert min(p["kn"] for p in stiff) > max(p["kn"] for p in base)
    assert {p["seed"] for p in stiff} == {p["seed"] for p in base}


def first_frame(path):
    """The first frame of a dump as a sorted list of atoms (type, x, y, z, ..., radius), ids left
    out: LAMMPS numbers the atoms by processor."""
    frame = path.read_text().split("ITEM: TIMESTEP")[1].splitlines()
    start = next(i for i, line in enumerate(frame) if line.startswith("ITEM: ATOMS"))
    return sorted(tuple(line.split()[1:]) for line in frame[start + 1:])


def test_the_start_does_not_depend_on_the_number_of_processors(tmp_path):
    """The sites kept, the sizes, the jitter and the base's heights come from positions, not
    atom ids: one and two ranks start from the same spheres (a partial top layer included)."""
    short = {**SMALL, "spheres": 70, "run_time": 0.2, "average_start": 0.1}
    one = run_scene("chute_3d", tmp_path / "np1", **short)
    two = run_scene("chute_3d", tmp_path / "np2", nprocs=2, **short)
    assert first_frame(one.workdir / "snapshots.lammpstrj") == \
        first_frame(two.workdir / "snapshots.lammpstrj")


# A chute that two ranks cut across the flow: LAMMPS splits the longest side of the box, here x
# (10.02 downhill, against 4.008 across and 7.85 high), so the spheres cross the cut as they
# flow and contacts straddle it at every step. The preset's law (kn 2e5, dt = tau_c/20). Two
# ranks sum the forces on an atom in another order than one: the same trajectory to rounding,
# and the flow is chaotic: it amplifies the first rounding difference by ~1e8 per time unit.
# Measured (positions and velocities at full precision, atoms matched by their start): 1 and 2
# ranks are equal to the bit at t = 3 and t = 4, 1e-16 apart at 5 and 5e-8 at 6; from ~6.5 on
# contacts begin at other steps (the counts differ) and by t ~ 8 the runs are two
# realizations of the flow (E 5-25 % apart). The span ends at 4, two time units before that.
SPLIT = dict(kn=2e5, dt_fraction=0.05, dt_cap=1, spheres=60, length=10, width=4,
             sin_theta=0.40, run_time=4, average_start=2, rows="yes")
# energy.txt's columns that are counts (integers in a double: summed exactly in any order)
COUNT_COLUMNS = ("step", "begun_disk", "begun_boundary", "contacts_now")
# "to rounding": the 2D decks' criterion (tests/lammps/test_consistency.py); energy.txt prints
# 10 digits
ROUNDING = 1e-8


def start_ids(directory):
    """{(type, x, y, z) at step 0: atom id} from the first frame of snapshots.lammpstrj."""
    frame = (Path(directory) / "snapshots.lammpstrj").read_text().split(
        "ITEM: TIMESTEP")[1].splitlines()
    assert int(frame[1]) == 0
    start = next(i for i, line in enumerate(frame) if line.startswith("ITEM: ATOMS"))
    assert frame[start].split()[2:6] == ["id", "type", "x", "y"]
    ids = {tuple(line.split()[1:5]): int(line.split()[0]) for line in frame[start + 1:]}
    assert len(ids) == len(frame) - start - 1, "two atoms start at one place"
    return ids


def same_atoms(reference, other):
    """{id in other: id in reference} of each atom: create_atoms numbers the atoms processor by
    processor, so that the ids depend on the number of ranks the run was started on; the start
    does not (the positions are hashes of the site), so an atom is known by where it started."""
    ours, theirs = start_ids(reference), start_ids(other)
    assert ours.keys() == theirs.keys(), "the runs do not start from the same spheres"
    return {theirs[key]: ours[key] for key in ours}


def counts_by_atom(directory, ids=None):
    """{atom id (translated by ids): (diameter, the six counters)} of counts.txt."""
    counts = read_counts(directory)
    columns = [name for name in counts if name != "id"]
    return {(ids or {}).get(int(i), int(i)): tuple(counts[c][k] for c in columns)
            for k, i in enumerate(counts["id"])}


def contact_rows(directory, ids=None):
    """The multiset of contacts.txt's (pair of ids, kind, start, duration) as printed: which of
    the two atoms' rows a pair is on follows the neighbour lists, so the pair is unordered."""
    rows = read_rows(directory)
    rename = (lambda i: (ids or {}).get(int(i), int(i)))
    return collections.Counter(
        (tuple(sorted((rename(i), rename(j)))), int(kind), start, duration)
        for i, j, kind, start, duration in zip(rows["id_i"], rows["id_j"], rows["kind"],
                                                rows["start"], rows["duration"]))


def assert_same_run(reference, other):
    """other's outputs are reference's, the atoms matched by their start: each sphere's counters
    exactly, the contacts' multiset exactly, the energies and the counters' time sums to
    rounding (a sum over the spheres in another order); the post-processing's observables to
    rounding. The number of contact rows, for the caller to judge the test's reach."""
    ids = same_atoms(reference, other)
    ours, theirs = counts_by_atom(reference), counts_by_atom(other, ids)
    assert len(ours) == 60 and ours.keys() == theirs.keys()
    differing = [i for i in ours if ours[i] != theirs[i]]
    assert not differing, [(i, ours[i], theirs[i]) for i in differing[:5]]
    rows = contact_rows(reference)
    assert rows == contact_rows(other, ids), (rows - contact_rows(other, ids),
                                              contact_rows(other, ids) - rows)
    a, b = energy_of(reference), energy_of(other)
    assert len(a["step"]) == len(b["step"])
    for name in ENERGY_COLUMNS:
        if name in COUNT_COLUMNS:
            assert np.array_equal(a[name], b[name]), name
        else:
            assert b[name] == pytest.approx(a[name], rel=ROUNDING, abs=1e-12), name
    mine, yours = point_observables(reference), point_observables(other)
    for name in ("N_c", "N_w", "t_c", "t_w", "E_total"):
        assert np.isfinite(mine[name]) and yours[name] == pytest.approx(mine[name], rel=ROUNDING)
    return sum(rows.values())


def test_two_ranks_cutting_the_flow_give_the_one_rank_counts(tmp_path):
    """The decomposition's bookkeeping: a contact across the cut is seen by both ranks (one
    owns the pair, the other a ghost), an atom that crosses it takes its contact histories and
    counters with it, a ghost's force is sent back to its owner. Any loss or double count (a
    contact counted begun on each side, its history restarted when the sphere changes rank, a
    row written twice or never, a ghost force dropped) changes the counts or the rows, and the
    trajectory at once (a force dropped moves spheres by ~1e-3 within a few steps)."""
    one = run_scene("chute_3d", tmp_path / "np1", **SPLIT)
    two = run_scene("chute_3d", tmp_path / "np2", nprocs=2, **SPLIT)
    assert "2 by 1 by 1 MPI processor grid" in (two.workdir / "log.lammps").read_text()
    rows = assert_same_run(one.workdir, two.workdir)
    kinds = {kind for _, kind, _, _ in contact_rows(one.workdir)}
    print(f"{rows} contact rows, the same from 1 and 2 ranks")
    assert rows > 500 and kinds == {1, 2}


def chute_config(tmp_path, variables):
    """A sweep config (tmp_path/chute.toml) of chute_3d points: the variables, a list a
    dimension of the grid."""
    path = tmp_path / "chute.toml"
    path.write_text('name = "c"\n[[grid]]\nscene = "chute_3d"\n' + "".join(
        f"{name} = {value!r}\n".replace("'", '"') for name, value in variables.items()))
    return path


# The same chute with checkpoints every 0.5 (at 0.5, 1, ..., 3.5; the counters' window opens at
# 1.5): a run killed past its checkpoint at 2 resumes mid-window, its counters half-way. The
# deck's default dt (tau_c/100, 80000 steps) makes the run long enough (~1 s) to be killed.
CHECKPOINTED = {**SPLIT, "dt_fraction": 0.01, "average_start": 1.5, "checkpoint_interval": 0.5,
                "stop_energy": 0}


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    """The checkpointed chute run through on one rank by the sweep runner."""
    from test_checkpoint import point_dir
    from test_sweep import sweep
    tmp = tmp_path_factory.mktemp("whole")
    sweep(chute_config(tmp, CHECKPOINTED), tmp / "out", "--jobs", "1")
    return point_dir(tmp / "out")


@pytest.mark.parametrize("killed_on, resumed_on", [(1, 1), (1, 2), (2, 1)])
def test_killed_chute_resumes_to_the_uninterrupted_counts(tmp_path, uninterrupted, killed_on,
                                                          resumed_on):
    """kill -9 of the sweep past the checkpoint at t = 2, then the same sweep again, with
    --ranks killed_on and resumed_on: the restart file holds the atoms, the contact histories and
    the counters' per-atom state and window, and LAMMPS reads it on any number of ranks. On the
    same rank count as the uninterrupted run every output is the same to the bit (as in 2D,
    tests/lammps/test_checkpoint.py: the same setups at the same steps); on another, each
    sphere's counters and the contacts exactly, the energies and profiles to rounding (the
    forces summed in another order; the span ends before the flow's chaos amplifies it). A
    counter's window restarted, a history dropped or a contact counted twice on resuming
    changes the counts."""
    if max(killed_on, resumed_on) > 1 and SERIAL:
        pytest.skip(SERIAL_REASON)
    from test_checkpoint import data_lines, kill_mid_chunk
    from test_sweep import sweep
    config = chute_config(tmp_path, CHECKPOINTED)
    ranks = ("--ranks", str(killed_on))
    directory, step = kill_mid_chunk(config, tmp_path / "killed", *ranks, after=4)
    with open(directory / "energy.txt", "a") as energy:    # a line the kill cut
        energy.write(f"{step + 10**6} 0.12")
    proc = sweep(config, tmp_path / "killed", "--jobs", "1", "--ranks", str(resumed_on))
    assert "1 to run" in proc.stdout
    log = (directory / "log.lammps").read_text()
    assert "resuming from checkpoint" in log
    assert ("2 by 1 by 1 MPI processor grid" in log) == (resumed_on == 2)
    assert not list(directory.glob("checkpoint*")), "checkpoints left after the run completed"
    if killed_on == resumed_on == 1:
        for name in ("energy.txt", "snapshots.lammpstrj", "counts.txt", "profile_chunks.txt",
                     "contacts.txt"):
            assert data_lines(directory / name) == data_lines(uninterrupted / name), name
    rows = assert_same_run(uninterrupted, directory)
    whole, resumed = read_profile(uninterrupted), read_profile(directory)
    for name, values in whole.items():
        assert resumed[name] == pytest.approx(values, rel=ROUNDING, abs=1e-12), name
    print(f"killed on {killed_on} rank(s) after step {step}, resumed on {resumed_on}: "
          f"{rows} contact rows as the uninterrupted run's")
