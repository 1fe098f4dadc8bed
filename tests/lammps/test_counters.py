"""fix contacts/mn: contact counts, contact times and per-contact rows."""
import struct

import numpy as np
import pytest

from collision_decks import DISC_DENSITY, bounces, disk_over_floor, two_disks
from granmn_run import HEADER, PLUGIN, law, restitution_error_bound, run_lammps, run_scene
from pile_decks import BETA, BOUNDARY, E, FIXES, KN, styles
from postprocess.io import CONTACT_KINDS, COUNTER_COLUMNS, ROW_COLUMNS, SCHEMA

COUNTS = "id f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6]"
SUMS = "$(f_c[1]) $(f_c[2]) $(f_c[3]) $(f_c[4]) $(f_c[5]) $(f_c[6]) $(f_c[7]) $(f_c[8])"
# the global vector's entries by name (plugin/mn_output_schema.h)
VECTOR = (*COUNTER_COLUMNS, *SCHEMA["vector_extras"])


@pytest.mark.parametrize("mu", [0.5, 0.0])
def test_binary_collision_is_one_contact_per_disk_lasting_tau_c(tmp_path, mu):
    """Also with mu = 0, where the pair style keeps no u_t and its loop for a frictionless law
    with a contact observer runs (a head-on collision: the same contact either way)."""
    material = (2e5, 0.7, 0.7, mu)
    tau = law(*material[:3])["tau_c"]
    dt = tau / 100
    deck, _ = two_disks(material, dt)
    deck = deck.replace("thermo 0\n", "fix c all contacts/mn local 1\n"
                        "dump rows all local 1 rows.txt f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] "
                        "f_c[6] f_c[7] f_c[8]\nthermo 0\n")
    deck += f"write_dump all custom counts.txt {COUNTS}\nprint \"RESULT sums {SUMS}\"\n"
    run = run_lammps(deck, tmp_path)
    counts = run.atoms("counts.txt")
    assert list(counts["f_c[1]"]) == [1, 1]            # one particle contact begun by each
    assert list(counts["f_c[2]"]) == [0, 0]
    assert np.all(np.abs(counts["f_c[3]"] - tau) <= dt)  # in contact for tau_c, to one step
    assert list(counts["f_c[5]"]) == [0, 0]            # never two contacts at once
    rows = [l.split() for l in (tmp_path / "rows.txt").read_text().splitlines()
            if l and not l.startswith("ITEM") and len(l.split()) == 8]
    assert len(rows) == 1                              # one completed contact, one row
    row = dict(zip(ROW_COLUMNS, map(float, rows[0])))
    assert {row["id_i"], row["id_j"]} == {1, 2} and row["kind"] == CONTACT_KINDS["disk"]
    assert abs(row["duration"] - tau) <= dt
    assert abs(-row["vn_end"] / row["vn_start"] - 0.7) < 0.01     # the collision's restitution
    # peak overlap of delta'' + 2 eta_n delta' + 2 kn delta = 0 from delta'(0) = 1:
    # (1/w) exp(-eta_n t*) sin(w t*) with w = pi/tau_c and tan(w t*) = w/eta_n; the sampled peak
    # carries the first-order error of the contact's start, as e does
    c = law(*material[:3])
    w = np.pi / tau
    t_peak = np.arctan2(w, c["eta_n"]) / w
    expected_peak = np.exp(-c["eta_n"] * t_peak) * np.sin(w * t_peak) / w
    assert abs(row["peak"] / expected_peak - 1) <= restitution_error_bound(0.7, dt / tau)
    sums = run.result("sums")
    assert sums[0] == 2 and sums[7] == 2


@pytest.mark.parametrize("mu", [0.5, 0.0])
def test_disk_resting_on_the_wall_touches_it_all_the_time(tmp_path, mu):
    """Also on a frictionless wall, whose fix keeps no u_t: the counters then add the wall
    fix's per-atom columns at init (they once registered it with LAMMPS there, too late: a
    wrong fix's callbacks, an error at exit or a crash in the first atom sort)."""
    kn = 2e5
    dt = law(kn, 0.7, 0.7)["tau_c"] / 50
    deck = f"""
{disk_over_floor(kn, 0.5 - 1.0 / kn, dt, mu=mu)}thermo 0
run 10000
print "RESULT sums {SUMS}"
"""
    sums = run_lammps(deck, tmp_path).result("sums")
    sums = dict(zip(VECTOR, sums))
    assert sums["begun_boundary"] == 1 and sums["begun_disk"] == 0
    assert sums["time_boundary"] / sums["window"] == pytest.approx(1.0, abs=1e-12)
    assert sums["contacts_now"] == 1 and sums["group_size"] == 1


def test_a_timestep_changed_within_a_run_counts_each_step_with_its_own(tmp_path):
    """fix dt/reset shortens the time step every 100 steps as a second disk falls faster (a
    step moves it 0.9 dt_0 at most): the disk resting on the wall touches it for LAMMPS's
    elapsed time, the sum of the steps as taken; a clock that took the last time step for the
    steps before it would be 8 % off, the window too."""
    kn = 2e5
    dt = law(kn, 0.7, 0.7)["tau_c"] / 50
    deck = f"""
{disk_over_floor(kn, 0.5 - 1.0 / kn, dt, mu=0.5)}thermo 0
create_atoms 1 single 2.0 4.0 0
set atom 2 diameter 1.0
set atom 2 density/disc {DISC_DENSITY!r}
group mobile type 1
velocity all set 0 0 0
set atom 2 vy -1.0
fix shorter all dt/reset 100 NULL {dt!r} {0.9 * dt!r} units box
run 1000
print "RESULT sums {SUMS} $(time:%.17g) $(dt:%.17g)"
"""
    values = run_lammps(deck, tmp_path).result("sums")
    t_boundary, window, elapsed, last_dt = values[3], values[6], values[8], values[9]
    print(f"elapsed {elapsed:.6g} = {elapsed / dt:.1f} dt_0; last dt {last_dt / dt:.3f} dt_0")
    assert last_dt < 0.85 * dt and elapsed < 0.9 * 1000 * dt
    assert t_boundary == pytest.approx(elapsed, rel=1e-12)
    assert window == pytest.approx(elapsed, rel=1e-12)


def test_bounces_before_lasting_contact_grow_linearly_with_ln_kn(tmp_path):
    """The rebound speed falls by e_w per bounce until it is of order g tau_w, below which the
    disk cannot leave the wall; tau_w ~ kn^-1/2, so the number of bounces is
    ln(kn) / (2 |ln e_w|) + const (docs/model.md section 7: it grows like ln kn). Slope tolerance: the
    count is an integer, +-1 over the fitted span of ln kn = 11.1, i.e. +-0.18 on ~2.0, plus the
    first-order time-step error in e_w."""
    kns = [2 ** p * 1e5 for p in range(0, 17, 2)]
    counts = np.array([bounces(tmp_path, kn) for kn in kns])
    x = np.log(kns)
    slope, intercept = np.polyfit(x, counts, 1)
    fitted = slope * x + intercept
    r2 = 1 - np.sum((counts - fitted) ** 2) / np.sum((counts - counts.mean()) ** 2)
    expected = 1 / (2 * abs(np.log(law(1e5, 0.7, 0.7)["e_w"])))
    print(f"bounces {counts.tolist()} slope {slope:.3f} (expected {expected:.3f}) R^2 {r2:.4f}")
    assert slope > 0
    assert r2 > 0.97
    assert abs(slope - expected) < 0.2 * expected


COUNTERS = """
fix c mobile contacts/mn local 100
dump rows mobile local 100 rows.txt f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6] f_c[7] f_c[8]
dump_modify rows format float %.10g
"""
HALF = 1500
FINAL_COUNTS = f"write_dump mobile custom counts.txt {COUNTS} modify sort id\n"


def counted_run(settled, workdir, newton="on", nprocs=1, integrator="nve/sphere disc"):
    deck = (f"newton {newton}\nprocessors * 1 1\n{BOUNDARY}read_data {settled}\n"
            "group mobile type 1\n" + styles(0.5, integrator=integrator) +
            COUNTERS + f"run {HALF}\nwrite_restart mid.restart\nrun {HALF}\n" + FINAL_COUNTS)
    return run_lammps(deck, workdir, nprocs=nprocs)


def counts_and_rows(run, after_step=-1):
    counts = run.atoms("counts.txt")
    table = np.column_stack([counts[f"f_c[{k}]"] for k in range(1, 7)])
    rows, step = [], None
    for line in (run.workdir / "rows.txt").read_text().splitlines():
        if line.startswith("ITEM: TIMESTEP"):
            step = "next"
        elif step == "next":
            step = int(line)
        elif not line.startswith("ITEM") and len(line.split()) == 8 and step > after_step:
            rows.append(tuple(float(x) for x in line.split()))
    return table, sorted(rows)


@pytest.fixture(scope="module")
def counted_reference(settled, tmp_path_factory):
    return counted_run(settled, tmp_path_factory.mktemp("reference"))


# Rows: tags and kind exact, start and duration (whole steps) and peak overlap to rounding,
# velocities to the rounding of the chaotic pile (test_consistency: positions agree to 1e-8,
# velocities to omega * 1e-8 ~ 6e-6).
ROW_TOLERANCE = np.array([0, 0, 0, 1e-9, 1e-9, 1e-5, 1e-5, 1e-8])


def assert_same_counts(a, b):
    """Counts exactly; times (sums of whole steps) and row values to rounding."""
    table_a, rows_a = a
    table_b, rows_b = b
    assert np.array_equal(table_a[:, [0, 1, 5]], table_b[:, [0, 1, 5]])
    assert np.allclose(table_a[:, 2:5], table_b[:, 2:5], rtol=0, atol=1e-9)
    assert len(rows_a) == len(rows_b)
    difference = np.abs(np.array(rows_a) - np.array(rows_b))
    assert np.all(difference <= ROW_TOLERANCE), difference.max(axis=0)


def test_pile_has_contacts_crossing_ranks(counted_reference):
    table, rows = counts_and_rows(counted_reference)
    print(f"contacts begun: particle {table[:, 0].sum():.0f}, boundary {table[:, 1].sum():.0f}; "
          f"completed rows {len(rows)}; multiple-contact time {table[:, 4].sum():.3f}")
    assert table[:, 0].sum() > 50 and table[:, 1].sum() > 5 and len(rows) > 20
    assert table[:, 4].sum() > 0


@pytest.mark.parametrize("newton,nprocs", [("off", 1), ("on", 2), ("off", 2)])
def test_counts_identical_with_newton_and_ranks(settled, counted_reference, tmp_path, newton,
                                                nprocs):
    other = counted_run(settled, tmp_path, newton=newton, nprocs=nprocs)
    assert_same_counts(counts_and_rows(counted_reference), counts_and_rows(other))


@pytest.mark.parametrize("nprocs", [1, 2])
@pytest.mark.parametrize("integrator", ["nve/sphere disc", "nve/ab2"])
def test_counts_continue_across_restart(settled, counted_reference, tmp_path, nprocs,
                                        integrator):
    reference = counted_reference
    if integrator != "nve/sphere disc":
        reference = counted_run(settled, tmp_path / "reference", integrator=integrator)
    deck = (f"read_restart {reference.workdir / 'mid.restart'}\n"
            "neighbor 0.1 bin\ncomm_modify vel yes\n" +
            FIXES.format(tilt=0.3, integrator=integrator) + COUNTERS +
            f"run {HALF}\n" + FINAL_COUNTS)
    restarted = run_lammps(deck, tmp_path / "restarted", nprocs=nprocs)
    assert_same_counts(counts_and_rows(reference, after_step=HALF), counts_and_rows(restarted))


BAD = {
    "unknown keyword": ("fix c all contacts/mn often 10", "unknown keyword often"),
    "local without N": ("fix c all contacts/mn local", "local needs N"),
    "local zero": ("fix c all contacts/mn local 0", "local N needs N > 0"),
    "every without M": ("fix c all contacts/mn every", "every needs M"),
    "every zero": ("fix c all contacts/mn every 0", "every M needs M > 0"),
    "per-atom output between its steps": (
        "fix c all contacts/mn every 10\ndump d all custom 5 d.txt id f_c[3]\nrun 0",
        "Dump custom and fix not computed at compatible times"),
    "reset with an argument": ("fix c all contacts/mn\nfix_modify c reset now",
                               "reset takes no arguments"),
    "two counter fixes": ("fix c all contacts/mn\nfix d all contacts/mn",
                          "Only one fix contacts/mn"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_counter_input(tmp_path, case):
    text, message = BAD[case]
    deck = f"""
region box block -3 3 -3 3 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 0 0
set type 1 density/disc {DISC_DENSITY!r}
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
timestep 1e-5
{text}
run 1
"""
    run = run_lammps(deck, tmp_path, check=False)
    assert run.returncode != 0 and message in run.output, run.output[-1500:]


def test_counters_without_the_gran_mn_styles(tmp_path):
    deck = f"""
region box block -3 3 -3 3 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 0 0
set type 1 density/disc {DISC_DENSITY!r}
pair_style gran/hooke 2e5 NULL 50 NULL 0.5 0
pair_coeff * *
fix c all contacts/mn
run 1
"""
    run = run_lammps(deck, tmp_path, check=False)
    assert run.returncode != 0 and "neither is defined" in run.output


@pytest.mark.parametrize("counters", [False, True])
def test_restart_with_a_different_contact_history_is_refused(settled, counted_reference,
                                                             tmp_path, counters):
    """A restart written with counters (u_t and 3 values per contact) read without them (u_t
    only), or the other way round, would misread every contact's history: it is an error."""
    if counters:    # a restart without counters, continued with them
        written = run_lammps(f"{BOUNDARY}read_data {settled}\ngroup mobile type 1\n" +
                             styles(0.5) + "run 10\nwrite_restart plain.restart\n",
                             tmp_path / "plain")
        restart, held, needed = written.workdir / "plain.restart", 1, 4
    else:
        restart, held, needed = counted_reference.workdir / "mid.restart", 4, 1
    deck = (f"read_restart {restart}\ncomm_modify vel yes\n" +
            FIXES.format(tilt=0.3, integrator="nve/sphere disc") +
            (COUNTERS if counters else "") + "run 10\n")
    run = run_lammps(deck, tmp_path / "continued", check=False)
    assert run.returncode != 0
    assert (f"the restart file holds {held} history values per contact, this run needs {needed}"
            in run.output), run.output[-1500:]


def test_a_timestep_changed_between_runs_keeps_the_window_and_the_rows_in_time(tmp_path):
    """The window length and the rows' start times are times, not step counts times the
    current dt: a resting disk's window after 1000 steps of dt and 1000 of dt/2 is 1500 dt (and
    it touched the floor throughout); two disks whose run switches to dt/2 before they meet
    start their contact when they meet, (pre_steps + 1/2) dt into the run."""
    kn = 2e5
    dt = law(kn, 0.7, 0.7)["tau_w"] / 50
    deck = f"""
{disk_over_floor(kn, 0.5 - 1.0 / kn, dt)}thermo 0
run 1000
timestep {dt / 2!r}
run 1000
print "RESULT window $(f_c[7]) $(f_c[4])"
"""
    window, touching = run_lammps(deck, tmp_path / "resting").result("window")
    assert window == pytest.approx(1500 * dt, rel=1e-12)
    assert touching == pytest.approx(1500 * dt, rel=1e-12)

    material = (kn, 0.7, 0.7, 0.5)
    tau = law(*material[:3])["tau_c"]
    deck, _ = two_disks(material, tau / 100, pre_steps=10)
    steps = deck.split("run ")[1].split()[0]
    deck = deck.replace(f"thermo 0\nrun {steps}\n",
                        "fix c all contacts/mn local 1\ndump rows all local 1 rows.txt f_c[4] "
                        f"f_c[5]\nthermo 0\nrun 5\ntimestep {tau / 200!r}\nrun {2 * int(steps)}\n")
    run_lammps(deck, tmp_path / "pair")
    rows, entries = [], False
    for line in (tmp_path / "pair" / "rows.txt").read_text().splitlines():
        if line.startswith("ITEM:"):
            entries = line.startswith("ITEM: ENTRIES")
        elif entries:
            rows.append(tuple(map(float, line.split())))
    (start, duration), = rows
    assert start == pytest.approx(10.5 * tau / 100, abs=tau / 100)    # found within a step
    assert duration == pytest.approx(tau, abs=tau / 200)


def test_two_wall_fixes_keep_their_own_contacts(tmp_path):
    """A floor and a side wall, each its own fix wall/gran/mn. A disk resting on the floor far
    from the side wall makes one boundary contact (begun at the start) and no rows; a disk
    resting in the corner, pressed into it by gravity, makes two (one per wall), still
    touching both at the end."""
    kn = 2e5
    dt = law(kn, 0.7, 0.7)["tau_w"] / 50

    def corner(x, name):
        deck = disk_over_floor(kn, 0.5 - 1.0 / kn, dt).replace(
            "create_atoms 1 single 0 ", f"create_atoms 1 single {x!r} ").replace(
            "vector 0 -1 0", "vector -0.3 -1 0").replace("boundary p f p", "boundary f f p")
        deck += f"""fix side mobile wall/gran/mn xplane -2.0 NULL
fix_modify c reset
dump rows all local 1 rows.txt f_c[1] f_c[2] f_c[3]
thermo 0
run 2000
print "RESULT sums $(f_c[2]) $(f_c[6])"
"""
        run = run_lammps(deck.replace("fix c mobile contacts/mn", "fix c mobile contacts/mn local 1"),
                         tmp_path / name)
        rows = [l for l in (tmp_path / name / "rows.txt").read_text().splitlines()
                if l and not l.startswith("ITEM") and len(l.split()) == 3 and l.split()[2] == "2"]
        return run.result("sums"), rows

    (begun, now), rows = corner(0.0, "floor_only")
    assert begun == 1 and now == 1 and rows == []
    (begun, now), rows = corner(-1.5 - 0.3 / kn, "corner")    # at its equilibrium overlap
    assert begun == 2 and now == 2 and rows == []


def test_frictional_scene_with_a_frictionless_wall_and_counters_runs(tmp_path):
    """inputs/frictional_flow.lmp -var mu 0 crashed (Atom::sort -> AtomVec::grow at the first
    run) when the wall fix, with no u_t to keep, got its per-atom columns from the counters
    only at init. It runs; the lowest row starts about 1.6 above the floor (centres at 2), so
    it lands within 2 time units: boundary contacts begun."""
    run = run_scene("frictional_flow", tmp_path, mu=0, run_time=2, average_start=1)
    assert run.atoms("counts.txt")["f_c[2]"].sum() > 0


def local_rows(path):
    """The rows of a dump local file, as tuples."""
    rows, entries = [], False
    for line in path.read_text().splitlines():
        if line.startswith("ITEM:"):
            entries = line.startswith("ITEM: ENTRIES")
        elif entries:
            rows.append(tuple(map(float, line.split())))
    return rows


@pytest.mark.parametrize("jump", [1000000, 0])
def test_reset_timestep_in_the_middle_of_a_contact_moves_the_step_not_the_clock(tmp_path,
                                                                               jump):
    """Two disks meet 10.5 steps into the run; half-way through their contact the step is
    reset, forward to 1e6 or back to 0. No time passes at a reset: the contact still lasts
    tau_c (to the step, as any contact), starts when they met, and the window after the run is
    the time of all steps taken. Back at step 0 its row is dumped once, not again at every
    step that follows."""
    material = (2e5, 0.7, 0.7, 0.5)
    tau = law(*material[:3])["tau_c"]
    dt = tau / 100
    deck, _ = two_disks(material, dt, pre_steps=10)
    steps = int(deck.split("run ")[1].split()[0])
    # LAMMPS 2025 refuses reset_timestep under an active dump: the dump is made again after it
    dump = "dump rows all local 1 rows.txt f_c[4] f_c[5]\ndump_modify rows append yes\n"
    deck = deck.replace(f"thermo 0\nrun {steps}\n",
                        f"fix c all contacts/mn local 1\n{dump}thermo 0\nrun 60\nundump rows\n"
                        f"reset_timestep {jump}\n{dump}run {steps - 60}\n"
                        "print \"RESULT window $(f_c[7])\"\n")
    run = run_lammps(deck, tmp_path)
    (start, duration), = local_rows(tmp_path / "rows.txt")
    assert start == pytest.approx(10.5 * dt, abs=dt)
    assert duration == pytest.approx(tau, abs=dt)
    assert run.result("window")[0] == pytest.approx(steps * dt, rel=1e-9)


RESTART_STEP = 1550    # not a multiple of the rows' 100 steps: rows are pending there


def restart_between_dumps(settled, workdir, nprocs):
    """The counted pile for 2 HALF steps, writing a restart file at step RESTART_STEP, between
    two dumps of the rows (two runs, so that the run continued from the file has its neighbor
    lists built at the same step: the same trajectory to rounding, hence the same contacts)."""
    deck = (f"processors * 1 1\n{BOUNDARY}read_data {settled}\ngroup mobile type 1\n" +
            styles(0.5) + COUNTERS + f"run {RESTART_STEP}\nwrite_restart mid.restart\n"
            f"run {2 * HALF - RESTART_STEP}\n" + FINAL_COUNTS)
    return run_lammps(deck, workdir, nprocs=nprocs)


@pytest.mark.parametrize("write_procs,read_procs", [(1, 2), (2, 1)])
def test_rows_pending_at_a_restart_are_dumped_by_the_run_that_continues(
        settled, tmp_path, write_procs, read_procs):
    """A contact that ends between two dumps of the rows waits for the next one: at a restart
    file written then, it is kept in the file, and the run continued from it dumps it. The rows
    of the first run up to its last dump before the restart, with those of the continued run,
    are the rows of the uninterrupted run; the final counts are its counts. The file is written
    on one process and read on two, and the other way round (the rows are gathered)."""
    reference = restart_between_dumps(settled, tmp_path / "reference", write_procs)
    deck = (f"read_restart {reference.workdir / 'mid.restart'}\n"
            "neighbor 0.1 bin\ncomm_modify vel yes\n" +
            FIXES.format(tilt=0.3, integrator="nve/sphere disc") + COUNTERS +
            f"run {2 * HALF - RESTART_STEP}\n" + FINAL_COUNTS)
    restarted = run_lammps(deck, tmp_path / "restarted", nprocs=read_procs)
    table, all_rows = counts_and_rows(reference)
    _, rows_after = counts_and_rows(reference, after_step=RESTART_STEP // 100 * 100)
    before = list(all_rows)
    for row in rows_after:
        before.remove(row)
    continued_table, continued_rows = counts_and_rows(restarted)
    dt = law(KN, E, BETA)["tau_c"] / 50
    pending = [row for row in rows_after if row[3] + row[4] <= RESTART_STEP * dt]
    print(f"rows: {len(before)} before step {RESTART_STEP // 100 * 100}, {len(pending)} pending at "
          f"the restart, {len(continued_rows)} after it")
    assert pending    # the test would not see a lost row otherwise
    assert_same_counts((continued_table, sorted(before + continued_rows)), (table, all_rows))


def earlier_layout(restart, target, layout):
    """The restart file as a version before 1 Dec 2026 wrote it: fix contacts/mn's global
    record holds the clock alone (layout -2: 4 values), or the clock, a row count and the rows
    as now but marked -3 (its per-atom state held the output columns only); this version writes
    -4. For -2 only a file with no rows pending (the count 0)."""
    data = restart.read_bytes()
    now_layout = struct.pack("=id", 5 * 8, -4.0)
    start = data.index(now_layout)
    if layout == -3:
        earlier = struct.pack("=id", 5 * 8, -3.0) + data[start + 12:]
    else:
        clock = data[start + 12:start + 36]
        assert struct.unpack("=d", data[start + 36:start + 44])[0] == 0.0
        earlier = struct.pack("=id", 4 * 8, -2.0) + clock + data[start + 44:]
    target.write_bytes(data[:start] + earlier)
    return target


@pytest.mark.parametrize("layout", [-2, -3])
def test_restart_file_of_an_earlier_layout_is_refused_with_its_date(counted_reference, tmp_path,
                                                                    layout):
    """A restart file whose counters record is of a layout before 1 Dec 2026 is refused by
    name, not read: the converter that read them (taking the per-atom times from the output
    columns) is gone, and a continued run would otherwise count from a state it misreads.
    Rules out reading such a file silently."""
    restart = earlier_layout(counted_reference.workdir / "mid.restart",
                             tmp_path / f"layout{-layout}.restart", layout)
    deck = (f"read_restart {restart}\nneighbor 0.1 bin\ncomm_modify vel yes\n" +
            FIXES.format(tilt=0.3, integrator="nve/sphere disc") + COUNTERS + f"run {HALF}\n")
    run = run_lammps(deck, tmp_path / "restarted", check=False)
    assert run.returncode != 0
    assert (f"ERROR: Fix contacts/mn: the restart file was written by a version of the gran/mn "
            f"plugin before 1 Dec 2026 (its counters record begins with {layout}, this "
            f"version's with -4)") in run.output, run.output[-1500:]


# The times against a direct per-step sum: the pile without its bumps (so that every contact
# of a disk is with another disk, which compute contact/atom counts, or with the floor or the
# lid, which its position tells), flowing, its counters read at odd intervals (per-atom every
# 7 steps, the sums every 13, thermo every 11) and continued from a restart file written at a
# step that is none of those multiples.
DIRECT_STEPS, DIRECT_RESTART, LID = 1400, 703, 11.5
DIRECT_OUTPUTS = """
fix c mobile contacts/mn every 7
compute touching all contact/atom
dump direct all custom 1 direct.txt id c_touching y radius
dump counters mobile custom 7 counters.txt id f_c[3] f_c[4] f_c[5] f_c[6]
dump_modify counters format float %.17g
fix sums all print 13 "$(step) $(f_c[3]:%.17g) $(f_c[4]:%.17g) $(f_c[5]:%.17g)" append sums.txt screen no
thermo_style custom step f_c[3] f_c[5]
thermo 11
"""


def frames(path):
    """step -> {id: values} of a LAMMPS text dump; a step written twice (a run's setup repeats
    the last step of the run before) keeps its first frame."""
    frames, lines, k = {}, path.read_text().splitlines(), 0
    while k < len(lines):
        step, n = int(lines[k + 1]), int(lines[k + 3])
        rows = np.loadtxt(lines[k + 9:k + 9 + n], ndmin=2)
        frames.setdefault(step, {int(row[0]): row[1:] for row in rows})
        k += 9 + n
    return frames


def test_times_equal_a_direct_per_step_sum(settled, tmp_path):
    """Each disk's times (touching disks, touching the floor or lid, two or more contacts) equal
    the sum of dt over the steps at which it touched so, counted directly at each step, also
    read at steps that are not output steps of the fix and across a restart file."""
    first = (f"newton on\n{BOUNDARY}read_data {settled}\ngroup mobile type 1\n"
             "group bumps type 2\ndelete_atoms group bumps compress no\n" + styles(0.5) +
             DIRECT_OUTPUTS + f"run {DIRECT_RESTART}\nwrite_restart half.restart\n")
    run = run_lammps(first, tmp_path)
    second = ("read_restart half.restart\nneighbor 0.1 bin\ncomm_modify vel yes\n" +
              FIXES.format(tilt=0.3, integrator="nve/sphere disc") + DIRECT_OUTPUTS +
              "dump_modify direct append yes\ndump_modify counters append yes\n" +
              f"run {DIRECT_STEPS - DIRECT_RESTART}\n")
    run_lammps(second, tmp_path)
    dt = law(KN, E, BETA)["tau_c"] / 50
    direct, counters = frames(tmp_path / "direct.txt"), frames(tmp_path / "counters.txt")
    ids = sorted(counters[0])
    # per step, per disk: touching a disk, the floor or the lid, two or more contacts
    totals = {i: np.zeros(3) for i in ids}
    expected, expected_sums, sum_now = {}, {}, np.zeros(3)
    for step in range(DIRECT_STEPS + 1):
        for i in ids:
            disks, y, radius = direct[step][i]
            walls = (y < radius) + (LID - y < radius)
            if step > 0:    # a run's setup adds no time (step 0); step 703 is run 1's last step
                touching = dt * np.array([disks > 0, walls > 0, disks + walls >= 2])
                totals[i] += touching
                sum_now += touching
        if step in counters:
            expected[step] = {i: totals[i].copy() for i in ids}
        expected_sums[step] = sum_now.copy()
    worst = max(np.abs(counters[step][i][:3] - expected[step][i]).max()
                for step in counters for i in ids)
    sums = np.loadtxt(tmp_path / "sums.txt", ndmin=2)
    worst_sum = max(np.abs(values - expected_sums[int(step)]).max() for step, *values in sums)
    multiple = sum(expected[DIRECT_STEPS][i][2] for i in ids)
    print(f"{len(counters)} readings of {len(ids)} disks, {len(sums)} of the sums; largest "
          f"difference {worst:.3g}, of the sums {worst_sum:.3g} (dt {dt:.3g}); "
          f"multiple-contact time {multiple:.3f}")
    assert DIRECT_RESTART % 7 and DIRECT_RESTART % 13 and len(sums) > 100
    assert multiple > 0 and sorted(counters) == list(range(0, DIRECT_STEPS + 1, 7))
    # a time off by one step of one disk, at any reading, would be dt: the sums of dt round
    # far below that
    assert worst < 1e-6 * dt and worst_sum < 1e-6 * dt
    # contacts now, exactly
    for step in counters:
        for i in ids:
            disks, y, radius = direct[step][i]
            assert counters[step][i][3] == disks + (y < radius) + (LID - y < radius)


def stack(map_array, deletion, dt):
    """Disk B resting on the floor, disk A resting on B, centres one above the other (the
    forces stay along y: the stack stands), placed at their static overlaps (A on B: g/kn,
    B on the floor: 2 g/kn, equal masses), with counters; `deletion` removes A. Without
    map_array, no atom map (LAMMPS's default)."""
    kn = 2e5
    floor_overlap, pair_overlap = 2.0 / kn, 1.0 / kn
    y_b = 0.5 - floor_overlap
    header = HEADER.format(plugin=PLUGIN)
    if not map_array:
        header = header.replace("atom_modify map array\n", "")
    return header + f"""
boundary p f p
region box block -3 3 -1 5 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 {y_b!r} 0
create_atoms 1 single 0 {y_b + 1.0 - pair_overlap!r} 0
set type 1 diameter 1.0
set type 1 density/disc {DISC_DENSITY!r}
group top id 2
pair_style gran/mn kn {kn!r} e 0.7 beta 0.7 mu 0.5
pair_coeff * *
timestep {dt!r}
fix integrate all nve/sphere disc
fix gravity all gravity 1.0 vector 0 -1 0
fix floor all wall/gran/mn yplane 0.0 NULL
fix c all contacts/mn
thermo 0
{deletion}
print "RESULT sums $(f_c[3]) $(f_c[4]) $(f_c[5]) $(f_c[6]) $(f_c[7])"
"""


DELETIONS = {
    # fix evaporate takes A out at step 1000 (before its force evaluation): B touched it at
    # steps 1..999
    "evaporate": ("region above block -3 3 1 5 -0.5 0.5\n"
                  "fix kill top evaporate 1000 1 above 4321\nrun 3000", 999),
    # between runs: B touched A at the 1000 steps of the first run
    "delete_atoms": ("run 1000\ndelete_atoms group top compress no\nrun 2000", 1000),
}


@pytest.mark.parametrize("map_array", [True, False])
@pytest.mark.parametrize("deletion", sorted(DELETIONS))
def test_a_deleted_partner_is_no_contact_any_more(tmp_path, deletion, map_array):
    """A disk deleted while in contact (fix evaporate during the run, delete_atoms between
    runs) takes the contact with it: its partner B, left resting on the floor, has touched a
    particle (and two things at once) for exactly the steps before the deletion, touches the
    floor all 3000 steps and has one contact now. On one process with atom_modify map array
    (contact changes applied at once, ghosts folded onto their atoms) the partner stayed "in
    contact" with the deleted disk for the rest of the run: 2 contacts now, its particle and
    multiple-contact times growing to the end; with no atom map (every step counted anew) it
    was right. Times are whole steps times dt, to a rounding."""
    dt = law(2e5, 0.7, 0.7)["tau_w"] / 50
    text, touched_steps = DELETIONS[deletion]
    run = run_lammps(stack(map_array, text, dt), tmp_path, header=False)
    t_particle, t_boundary, t_multiple, now, window = run.result("sums")
    assert now == 1
    assert t_particle == pytest.approx(touched_steps * dt, rel=1e-12)
    assert t_multiple == pytest.approx(touched_steps * dt, rel=1e-12)
    assert t_boundary == pytest.approx(3000 * dt, rel=1e-12)
    assert window == pytest.approx(3000 * dt, rel=1e-12)



@pytest.mark.parametrize("map_array", [True, False])
@pytest.mark.parametrize("deletion", sorted(DELETIONS))
def test_a_deleted_partners_contact_takes_its_energy_with_it(tmp_path, deletion, map_array):
    """The energies' columns (energy yes) after the deletion of A, as the counters above: the
    energy stored now is the spring of B's floor contact alone, 0.5 k_n (0.5 - y_B)^2 (B
    sits on the floor, its forces along y), and what B's contact with A dissipated stays in the
    sums. A contact with the deleted disk kept (the counters' old fault) would add its spring,
    0.5 k_n overlap^2 with A's last overlap (1/k_n at rest), to the same order as the floor's.
    The stack starts with its springs loaded (the floor's 2/k_n, the pair's 0.5/k_n): the
    contacts' accounts open with that energy at the setup, so that what B's sums say was
    dissipated closes B's budget: the floor's spring at the start and B's half of the pair's
    (the half that stays in B's sums when the contact goes with A) = what is stored now + B's
    rise against gravity + B's kinetic energy + dissipated, to velocity Verlet's residual
    (dt^2/8) |F now|^2/m, where the force on B jumps by A's weight at a deletion between runs
    (delete_atoms: 2.5e-9 of 1.1e-5; fix evaporate, within a step, leaves none). An account
    opened at zero books B's release from the load as negative dissipation (-7.5e-6, against
    +3.75e-6); one opened twice books what the springs held twice (+1.125e-5)."""
    kn = 2e5
    dt = law(kn, 0.7, 0.7)["tau_w"] / 50
    text, _ = DELETIONS[deletion]
    first = len(VECTOR) + 1
    energies = " ".join(f"$(f_c[{first + k}]:%.17g)" for k in range(len(SCHEMA["energy_sums"])))
    deck = stack(map_array, text, dt).replace("fix c all contacts/mn",
                                              "fix c all contacts/mn energy yes")
    # B is the one atom left: the bounds of the group and its centre-of-mass velocity are its own
    deck += (f'print "RESULT energies {energies}"\n'
             'print "RESULT b $(bound(all,ymax):%.17g) $(vcm(all,x):%.17g) $(vcm(all,y):%.17g) '
             '$(mass(all):%.17g)"\n')
    run = run_lammps(deck, tmp_path, header=False)
    sums = dict(zip(SCHEMA["energy_sums"], run.result("energies")))
    y_b, vx, vy, mass = run.result("b")
    assert 0.5 - y_b > 0.5 / kn               # B still presses the floor
    assert sums["stored"] == pytest.approx(0.5 * kn * (0.5 - y_b) ** 2, rel=1e-9)
    assert sums["work_in_flight"] == pytest.approx(0.0, abs=1e-15)
    dissipated = sum(sums[name] for name in
                     ("dissipated_normal", "dissipated_sticking", "dissipated_sliding"))
    y_b_start = 0.5 - 2.0 / kn                # the stack's floor overlap (stack())
    held = 0.5 * kn * (2.0 / kn) ** 2 + 0.5 * (0.5 * kn * (1.0 / kn) ** 2)
    accounted = (sums["stored"] + mass * 1.0 * (y_b - y_b_start) + 0.5 * mass * (vx ** 2 + vy ** 2)
                 + dissipated)
    print(f"dissipated {dissipated:.6e}; springs' energy at the start booked to B {held:.6e}, "
          f"accounted for at the end {accounted:.6e}")
    jump = mass * 1.0                         # A's weight, off B at once
    assert abs(accounted - held) <= 1.01 * dt ** 2 / 8 * jump ** 2 / mass


def resting_on_walls(counters_first, map_array):
    """Disk 1 resting on the floor (fix wall/gran/mn), disk 2 resting on disk 1, disk 3 resting
    on the floor where a region wall's face (fix wall/gran/region/mn) lies on it too, each at
    its static overlap: contacts now 2 (disk 1: the floor, disk 2), 1 (disk 2), 2 (disk 3: both
    walls), 5 in all, at every step. fix contacts/mn is defined before the wall fixes or after them; with an atom map
    or without."""
    kn = 2e5
    header = HEADER.format(plugin=PLUGIN)
    if not map_array:
        header = header.replace("atom_modify map array\n", "")
    counters = "fix c all contacts/mn\n"
    walls = ("fix floor all wall/gran/mn yplane 0.0 NULL\n"
             "region shelf block 2 5 0 5 -0.5 0.5 units box\n"
             "fix shelf all wall/gran/region/mn shelf\n")
    return header + f"""
boundary p f p
processors * 1 1
region box block -3 6 -1 5 -0.5 0.5
create_box 1 box
create_atoms 1 single 0 {0.5 - 2.0 / kn!r} 0
create_atoms 1 single 0 {1.5 - 2.0 / kn - 1.0 / kn!r} 0
create_atoms 1 single 3.5 {0.5 - 0.5 / kn!r} 0
set type 1 diameter 1.0
set type 1 density/disc {DISC_DENSITY!r}
pair_style gran/mn kn {kn!r} e 0.7 beta 0.7 mu 0.5
pair_coeff * *
timestep {law(kn, 0.7, 0.7)["tau_w"] / 50!r}
fix integrate all nve/sphere disc
fix gravity all gravity 1.0 vector 0 -1 0
{counters + walls if counters_first else walls + counters}compute now all reduce sum f_c[6]
thermo_style custom step f_c[6] c_now
thermo_modify norm no
thermo 1000
run 100
run 100
run 0
write_dump all custom now.txt id f_c[6] modify sort id
group top id 2
delete_atoms group top compress no
run 0
"""


@pytest.mark.parametrize("nprocs", [1, 2])
@pytest.mark.parametrize("map_array", [True, False])
@pytest.mark.parametrize("counters_first", [True, False])
def test_contacts_now_at_every_runs_start(tmp_path, counters_first, map_array, nprocs):
    """The global "contacts now" (f_c[6]) and the sum of the per-atom column are the contacts
    there are, 5, at the start (setup) and end of each of three runs, whatever the order of
    the fixes, with or without an atom map, on one or two ranks (the stack on one, disk 3 on the
    other); per atom 2, 1, 2; after disk 2 is deleted, 3 at the next run's start. Where the
    counters were defined before the wall fixes, without an atom map or on two ranks, each
    run's setup dropped the wall contacts (the walls had not evaluated yet), and a run that
    started at the step the last one ended at gave the global value of that step (5)."""
    run = run_lammps(resting_on_walls(counters_first, map_array), tmp_path, nprocs=nprocs,
                     header=False)
    rows, header = [], False
    for line in run.output.splitlines():
        words = line.split()
        if words[:3] == ["Step", "f_c[6]", "c_now"]:
            header = True
        elif header and len(words) == 3 and words[0].isdigit():
            rows.append([float(w) for w in words])
        else:
            header = False
    print(rows)
    assert [row[0] for row in rows] == [0, 100, 100, 200, 200, 200]
    assert all(row[1:] == [5, 5] for row in rows[:-1]) and rows[-1][1:] == [3, 3]
    assert list(run.atoms("now.txt")["f_c[6]"]) == [2, 1, 2]
