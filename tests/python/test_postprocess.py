"""postprocess on synthetic outputs with known answers."""
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from postprocess.io import DataError, numeric_table, read_counts, read_energy, read_params  # noqa
from postprocess.observables import point_observables, span_rates
from postprocess.selection import select_steady, steady_spans
from postprocess.signals import dominant_period, trend

RNG = np.random.default_rng(7)


def wiggle(n, width):
    """Bounded fluctuation of total width just under `width`."""
    return 0.49 * width * np.sin(np.arange(n) * 0.7) * RNG.uniform(0.5, 1.0, n)


# ---- the steady-state selection (docs/model.md section 5), hand-worked cases

def test_a_series_that_stops_has_no_selected_part():
    t = np.arange(0, 2000, 1.0)
    e = np.where(t < 600, 0.6 + 1.5 * np.sin(t), 0.0)    # wild flow, then at rest
    kept, found = select_steady(t, e)
    assert found == [(600, 2000)]          # the rest is steady ...
    assert kept == []                      # ... but its energy 0 is outside [0.4, 0.8]


def test_a_series_that_jumps_keeps_only_the_part_in_range():
    t = np.arange(0, 2000, 1.0)
    e = np.where(t < 800, 0.6, 1.5) + wiggle(len(t), 0.3)
    kept, found = select_steady(t, e)
    assert found == [(0, 800), (800, 2000)]
    assert kept == [(0, 800)]


def test_a_flow_within_range_is_selected_whole():
    t = np.arange(0, 1500, 0.5)
    e = 0.55 + wiggle(len(t), 0.4)
    kept, found = select_steady(t, e)
    assert kept == found == [(0, len(t))]


def test_spans_must_be_longer_than_500_and_narrower_than_045():
    t = np.arange(0, 1000, 1.0)
    e = 0.6 + 0.5 * (t % 450 < 1)          # a spike every 450: no narrow span longer than 500
    assert steady_spans(t, e) == []
    e = 0.6 + 0.44 * (t % 2)               # width 0.44 < 0.45 everywhere
    assert steady_spans(t, e) == [(0, 1000)]


# ---- rates from cumulative counter sums

def energy_table(t, rates, n):
    """energy.txt columns for counters growing linearly at the given per-disk rates."""
    table = {"time": t}
    for key, rate in rates.items():
        table[key] = rate * n * (t - t[0])
    return table


def test_span_rates_recover_the_rates():
    t = np.arange(0, 100, 0.1)
    rates = dict(begun_disk=3.0, begun_boundary=0.5, time_disk=0.2, time_boundary=0.1,
                 time_multiple=0.05)
    r = span_rates(energy_table(t, rates, 50), [(0, len(t))], 50, 50)
    assert r["N_c"] == pytest.approx(3.0) and r["t_w"] == pytest.approx(0.1)
    # per bottom-layer disk: the same boundary counts over 10 disks
    r = span_rates(energy_table(t, rates, 50), [(0, 500), (600, 900)], 50, 10)
    assert r["N_w"] == pytest.approx(0.5 * 50 / 10)


# ---- a whole synthetic point

def completed(point):
    """What the deck and the sweep runner leave in a point whose run ended (postprocess.rundir):
    done.txt and timing.json, both carrying the run's token."""
    (point / "done.txt").write_text("kn 1 steps 1 dt 1 run t0\n")
    (point / "timing.json").write_text('{"seconds": 1.0, "cpu_seconds": 1.0, "run": "t0"}\n')
    return point


def write_point(tmp_path, scene="collisional_flow", n=4, run_time=100.0, average_start=20.0,
                dt=0.001, e_level=0.6, truncate=False):
    tau_c, tau_w = 0.005, 0.007
    (tmp_path / "params.txt").write_text(
        f"scene {scene}\nkn 200000\ne 0.7\nbeta 0.7\nmu 0.5\nsin_theta 0.2\nintegrator verlet\n"
        f"dt {dt}\ntau_c {tau_c}\ntau_w {tau_w}\nseed 1\nrun_time {run_time}\n"
        f"average_start {average_start}\nn_mobile {n}\n")
    lines = ["# energy and counters", "# step e_trans e_rot e_total begun_disk begun_boundary "
             "time_disk time_boundary time_multiple contacts_now window"]
    for step in range(0, int(run_time / dt) + 1, 100):
        t = step * dt
        # as the decks write it: the counters run from the start until average_start, the row of
        # that very step still holds those sums, and the window restarts after it
        w = t if t <= average_start else t - average_start
        # per disk: 2 disk contacts and 1 wall contact per unit time, 0.02 and 0.01 of the time
        counters = [2 * n * w, 1 * n * w, 0.02 * n * w, 0.01 * n * w, 0.001 * n * w, 1, w]
        e = e_level + 0.01 * np.sin(t)
        lines.append(" ".join(str(v) for v in [step, 0.9 * e, 0.1 * e, e] + counters))
    if truncate:
        lines[-1] = lines[-1][:20]
    (tmp_path / "energy.txt").write_text("\n".join(lines) + "\n")
    atoms = "\n".join(f"{i} 1.0 {2 * (run_time - average_start)} 80 1 1 0.1 1"
                      for i in range(1, n + 1))
    (tmp_path / "counts.txt").write_text(
        f"ITEM: TIMESTEP\n{int(run_time / dt)}\nITEM: NUMBER OF ATOMS\n{n}\nITEM: BOX BOUNDS pp fm pp\n"
        f"0 1\n0 1\n0 1\nITEM: ATOMS id diameter f_c[1] f_c[2] f_c[3] f_c[4] f_c[5] f_c[6]\n"
        f"{atoms}\n")
    return tmp_path


def test_point_observables_of_a_synthetic_collisional_point(tmp_path):
    o = point_observables(write_point(tmp_path))
    assert o["N_c"] == pytest.approx(2.0) and o["N_w"] == pytest.approx(1.0)
    assert o["t_c"] == pytest.approx(0.02) and o["t_w"] == pytest.approx(0.01)
    assert o["mc_c"] == pytest.approx(0.02 - 2.0 * 0.005)
    assert o["mc_w"] == pytest.approx(0.01 - 1.0 * 0.007)
    assert o["t_multiple"] == pytest.approx(0.001)
    assert o["E_total"] == pytest.approx(0.6, abs=0.01)
    assert o["N_c_err"] == pytest.approx(0.0, abs=1e-9)       # exact rates: no spread
    assert o["E_total_err"] > 0


def test_frictional_point_uses_the_selection_and_the_bottom_layer(tmp_path):
    o = point_observables(write_point(tmp_path, scene="frictional_flow", run_time=700.0,
                                      dt=0.01, average_start=100.0))
    assert "1 of 1 steady parts selected" in o["notes"]
    assert o["n_boundary"] == 4 and o["N_w"] == pytest.approx(1.0)


def test_frictional_point_outside_the_energy_range_is_refused(tmp_path):
    point = write_point(tmp_path, scene="frictional_flow", run_time=700.0, dt=0.01,
                        average_start=100.0, e_level=1.2)
    with pytest.raises(DataError, match="no steady part with mean energy in"):
        point_observables(point)


@pytest.mark.parametrize("damage,message", [
    ("truncate", "columns, expected 11"),
    ("header", "the header names no column time_multiple"),
    ("counts header", "names no column f_c\\[3\\]"),
    ("no params", "params.txt: missing"),
    ("short run", "before run_time"),
    ("counts", "atoms, the header says"),
    ("nan", r"energy.txt:6: e_trans is nan, not a finite number"),
    ("word", "not a number"),
    # values no run writes, which the summary reader refused and the raw reader averaged (only
    # numpy's overflow warnings): an energy of 1e308 in one row, a negative kinetic energy
    ("huge", r"energy.txt:6: e_total is 1e\+308, beyond 1e\+150 in magnitude, more than any "
             r"energy, rate, time or count of a run \(a damaged file\?\)"),
    ("negative", r"energy.txt:6: e_trans is -0.5, negative: it is an energy, a rate, a time "
                 "fraction or a count"),
    ("negative counter", r"energy.txt:6: time_disk is -1, negative"),
    ("negative count", r"counts.txt: atom 2 of the snapshot: f_c\[1\] is -160, negative"),
    # a hand-edited params.txt, or one another tool wrote: its last value was taken
    ("params twice", r"params.txt:15: kn given twice \(line 2 gives it too\): which value the "
                     "run took cannot be told"),
])
def test_broken_outputs_name_the_file_and_the_problem(tmp_path, damage, message):
    point = write_point(tmp_path, truncate=(damage == "truncate"))
    if damage == "negative count":
        lines = (point / "counts.txt").read_text().splitlines()
        lines[-3] = lines[-3].replace(" 160.0 ", " -160.0 ")
        (point / "counts.txt").write_text("\n".join(lines) + "\n")
    if damage == "params twice":
        with open(point / "params.txt", "a") as params:
            params.write("kn 100000\n")
    if damage in ("huge", "negative", "negative counter"):
        lines = (point / "energy.txt").read_text().splitlines()
        words = lines[5].split()
        column, value = {"huge": (3, "1e308"), "negative": (1, "-0.5"),
                         "negative counter": (6, "-1")}[damage]
        words[column] = value
        lines[5] = " ".join(words)
        (point / "energy.txt").write_text("\n".join(lines) + "\n")
    if damage == "no params":
        (point / "params.txt").unlink()
    if damage == "counts header":
        text = (point / "counts.txt").read_text()
        (point / "counts.txt").write_text(text.replace("f_c[3]", "f_c[9]"))
    if damage == "header":
        text = (point / "energy.txt").read_text()
        (point / "energy.txt").write_text(text.replace(" time_multiple", " t_multiple"))
    if damage == "short run":
        lines = (point / "energy.txt").read_text().splitlines()
        (point / "energy.txt").write_text("\n".join(lines[:len(lines) // 2]) + "\n")
    if damage == "counts":
        lines = (point / "counts.txt").read_text().splitlines()
        (point / "counts.txt").write_text("\n".join(lines[:-1]) + "\n")
    if damage in ("nan", "word"):
        lines = (point / "energy.txt").read_text().splitlines()
        lines[5] = lines[5].replace(lines[5].split()[1], "nan" if damage == "nan" else "x1")
        (point / "energy.txt").write_text("\n".join(lines) + "\n")
    with pytest.raises(DataError, match=message):
        point_observables(point)


# ---- signals

def test_dominant_period_of_a_known_signal():
    t = np.arange(0, 200, 0.1)
    period, strength = dominant_period(t, np.sin(2 * np.pi * t / 4.2) + 0.3 * np.sin(2 * np.pi * t / 2.1))
    assert period == pytest.approx(4.2, abs=0.1) and strength > 0.9


def test_a_motion_repeating_every_second_bump_has_the_bump_period():
    """Two bumps a little different in turn: the autocorrelation peaks higher at 8.4 than at
    4.2, but the bump period is 4.2."""
    t = np.arange(0, 400, 0.1)
    y = np.sin(2 * np.pi * t / 4.2) + 0.2 * np.sin(2 * np.pi * t / 8.4)
    period, strength = dominant_period(t, y)
    assert period == pytest.approx(4.2, abs=0.1) and strength > 0.8


def test_trend_of_noise_and_of_a_ramp():
    t = np.arange(0, 1000, 1.0)
    noise = RNG.normal(0, 1, len(t))
    slope, error = trend(t, noise, 0, 1000)
    assert abs(slope) < 4 * error
    slope, error = trend(t, noise + 0.01 * t, 0, 1000)
    assert slope == pytest.approx(0.01, abs=4 * error)


PROFILE_BINS = ["1 0.125 2 0.5 0.1 0.0", "2 0.375 1 0.25 0.2 0.0", "3 0.625 0 0 0 0"]


def write_profile(point, bins=PROFILE_BINS):
    """profile.txt as fix ave/chunk writes it: one block of 3 bins."""
    (point / "profile.txt").write_text("# fix ave/chunk\n# header\n# columns\n1000 3 3\n" +
                                       "\n".join(bins) + "\n")


@pytest.mark.parametrize("damage,message", [
    ("word", r"profile.txt:\d+: not a number"),
    ("short", "does not have 6 columns"),
    ("missing bin", "bins, the header says 3: truncated"),
])
def test_broken_profile_names_the_file_and_the_problem(tmp_path, damage, message):
    from postprocess.io import read_profile
    bins = list(PROFILE_BINS)
    if damage == "word":
        bins[1] = bins[1].replace("0.25", "x.25")
    if damage == "short":
        bins[1] = "2 0.375 1"
    if damage == "missing bin":
        bins = bins[:2]
    write_profile(tmp_path, bins)
    with pytest.raises(DataError, match=message):
        read_profile(tmp_path)


def contact_rows_snapshot(names, entries):
    """One snapshot of a dump local as LAMMPS writes it, its columns named `names`."""
    return ("ITEM: TIMESTEP\n100\nITEM: NUMBER OF ENTRIES\n" + f"{len(entries)}\n" +
            "ITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n" + f"ITEM: ENTRIES {' '.join(names)}\n" +
            "".join(line + "\n" for line in entries))


ROW_NAMES = [f"f_c[{k}]" for k in range(1, 9)]


def test_broken_contact_rows_name_the_line(tmp_path):
    from postprocess.io import read_rows
    (tmp_path / "contacts.txt").write_text(
        contact_rows_snapshot(ROW_NAMES, ["1 2 1 0.1 0.005 -1 0.7 nan?"]))
    with pytest.raises(DataError, match=r"contacts.txt:10: not a number"):
        read_rows(tmp_path)


def test_contact_rows_are_read_by_their_header(tmp_path):
    """The columns by the dump's own names, in whatever order a deck dumps them; a header
    without one of the fix's columns is refused, not read by position."""
    from postprocess.io import read_rows
    order = [7, 0, 1, 2, 3, 4, 5, 6]    # the peak overlap first
    row = [1, 2, 1, 0.1, 0.005, -1, 0.7, 0.01]
    (tmp_path / "contacts.txt").write_text(
        contact_rows_snapshot([ROW_NAMES[k] for k in order], [" ".join(str(row[k]) for k in order)])
        + contact_rows_snapshot(ROW_NAMES, [" ".join(str(v) for v in row)]))
    rows = read_rows(tmp_path)
    assert list(rows["peak"]) == [0.01, 0.01] and list(rows["id_j"]) == [2, 2]
    assert list(rows["duration"]) == [0.005, 0.005]
    (tmp_path / "contacts.txt").write_text(
        contact_rows_snapshot(ROW_NAMES[:7] + ["c_other"], [" ".join(str(v) for v in row)]))
    with pytest.raises(DataError, match=r"contacts.txt:9: the header .* names no column f_c\[8\]"):
        read_rows(tmp_path)


# ---- the selection at a time resolution (docs/model.md section 5: E(t) averaged over windows)

def test_window_means_average_consecutive_windows():
    from postprocess.selection import window_means
    t = np.arange(0, 10, 0.1)
    starts, means, edges = window_means(t, t, 1.0)
    assert len(starts) == 10 and list(edges[:3]) == [0, 10, 20]
    assert means == pytest.approx(np.arange(10) + 0.45)
    # a resolution at or below the sample spacing keeps the samples
    _, same, _ = window_means(t, t, 0.1)
    assert same == pytest.approx(t)


def test_a_steady_flow_with_wide_instantaneous_noise_is_kept_at_resolution_1():
    from postprocess.selection import Selection, select_at_resolution
    t = np.arange(0, 1200, 0.1)
    e = 0.65 + RNG.uniform(-0.3, 0.3, len(t))          # samples spread 0.6 > 0.45
    kept, _ = select_at_resolution(t, e, Selection(resolution=0.1))
    assert kept == []                                  # instantaneous samples: too wide
    kept, found = select_at_resolution(t, e, Selection(resolution=1.0))
    assert kept == found == [(0, len(t))]              # the 1-unit means: narrow, kept whole


def test_a_drifting_mean_is_rejected_at_every_resolution():
    from postprocess.selection import Selection, select_at_resolution
    t = np.arange(0, 1200, 0.1)
    e = 0.3 + 0.0012 * t + RNG.uniform(-0.05, 0.05, len(t))   # 0.6 over any 500 time units
    for resolution in (0.1, 1.0, 5.0):
        assert select_at_resolution(t, e, Selection(resolution=resolution))[0] == []


# ---- runs that stop

def stop_point(point, at):
    """Cut a synthetic point's energy.txt at time `at` and mark it stopped there, as the deck
    does when its pile comes to rest."""
    lines = (point / "energy.txt").read_text().splitlines()
    keep = [l for l in lines if l.startswith("#") or float(l.split()[0]) * 0.01 <= at]
    (point / "energy.txt").write_text("\n".join(keep) + "\n")
    (point / "stopped.txt").write_text(f"stopped_at {at}\n")
    return point


def test_a_run_stopped_after_a_steady_part_keeps_it_and_says_it_stopped(tmp_path):
    point = stop_point(write_point(tmp_path, scene="frictional_flow", run_time=1000.0, dt=0.01,
                                   average_start=100.0), 700.0)
    o = point_observables(point)
    assert "stopped at t = 700" in o["notes"] and "1 of 1 steady parts selected" in o["notes"]
    assert o["N_c"] == pytest.approx(2.0) and o["span"] == pytest.approx(600, abs=1.5)


def test_a_run_stopped_before_its_averaging_span_is_named_so(tmp_path):
    point = stop_point(write_point(tmp_path, scene="frictional_flow", run_time=1000.0, dt=0.01,
                                   average_start=100.0), 40.0)
    with pytest.raises(DataError, match="stopped at t = 40, before the averaging span"):
        point_observables(point)


def test_a_broken_stop_record_is_named(tmp_path):
    point = write_point(tmp_path, scene="frictional_flow", run_time=700.0, dt=0.01,
                        average_start=100.0)
    (point / "stopped.txt").write_text("stopped_at soon\n")
    with pytest.raises(DataError, match="stopped.txt:1: not a number"):
        point_observables(point)


# ---- the claims on a synthetic study with known exponents

def synthetic_rows(kn, label="", **laws):
    """Rows of a scene whose quantities follow the given functions of kn (errors 1 %)."""
    rows = []
    for k in kn:
        o = {"kn": k, "label": label}
        for q in ("E_total", "N_c", "N_w", "t_c", "t_w", "mc_c", "mc_w", "period", "bump_time"):
            o[q] = laws.get(q, lambda k: 1.0)(k)
            o[q + "_err"] = 0.01 * abs(o[q])
        rows.append(o)
    return rows


def test_claims_are_evaluated_on_the_main_series_only():
    from postprocess.reference import evaluate
    from postprocess.study import main_series, variant_differences
    kn = 1e5 * 2.0 ** np.arange(-3, 8)
    main = synthetic_rows(kn, N_c=lambda k: k ** 0.4)
    check = synthetic_rows(kn[:2], label="integrator ab2", N_c=lambda k: 5.0)
    rows = sorted(main + check, key=lambda o: o["kn"])
    assert main_series(rows) == main
    results = {c["id"]: (v, s) for c, v, _, s in evaluate({"frictional_flow": rows})}
    assert results["frictional-Nc"] == (pytest.approx(0.4), "pass")
    pairs = variant_differences(rows)
    assert [o["kn"] for o, _, _ in pairs] == list(kn[:2])
    d, sigmas = pairs[0][2]["N_c"]
    assert d == pytest.approx(5.0 - kn[0] ** 0.4)


@pytest.mark.parametrize("option,message", [
    (["--resolution", "0"], "--resolution 0 must be > 0"),
    (["--energy-range", "0.8", "0.4"], "--energy-range 0.8 0.4 must satisfy 0 <= LOW < HIGH"),
])
def test_selection_options_that_make_no_sense_are_refused(tmp_path, capsys, option, message):
    from postprocess.__main__ import main
    with pytest.raises(SystemExit) as stop:
        main(["compare", str(tmp_path)] + option)
    assert stop.value.code == 2 and message in capsys.readouterr().err


def test_a_wider_energy_range_keeps_a_flow_the_papers_range_refuses(tmp_path):
    from postprocess.selection import Selection
    point = write_point(tmp_path, scene="frictional_flow", run_time=700.0, dt=0.01,
                        average_start=100.0, e_level=0.95)
    with pytest.raises(DataError, match=r"no steady part with mean energy in \[0.4, 0.8\]"):
        point_observables(point)
    o = point_observables(point, selection=Selection(energy_range=(0.3, 1.2)))
    assert o["E_total"] == pytest.approx(0.95, abs=0.01)


def test_run_summary_counts_flowing_stopped_and_selected():
    from postprocess.study import run_summary
    runs = [dict(kn=1e5, label="", state="flowing", stopped_at=None, selected=True,
                 kept={0.1: 0, 1.0: 2, 5.0: 2}, cpu_seconds=30.0),
            dict(kn=1e5, label="", state="stopped", stopped_at=300.0, selected=False,
                 kept={0.1: 0, 1.0: 0, 5.0: 1}, cpu_seconds=4.5),
            dict(kn=2e5, label="", state="flowing", stopped_at=None, selected=False,
                 kept={0.1: 0, 1.0: 0, 5.0: 0}, cpu_seconds=None)]
    summary = run_summary(runs)
    assert list(summary) == [(1e5, ""), (2e5, "")]
    row = summary[(1e5, "")]
    assert (row["runs"], row["flowing"], row["stopped"], row["selected"]) == (2, 1, 1, 1)
    assert row["kept"] == {0.1: 0, 1.0: 2, 5.0: 3} and row["stop_times"] == [300.0]
    # the CPU time summed over the runs that have one; a run without it is counted as untimed
    assert (row["cpu_seconds"], row["timed"]) == (34.5, 2)
    assert (summary[(2e5, "")]["cpu_seconds"], summary[(2e5, "")]["timed"]) == (0.0, 0)


# ---- sweeps that are empty, or hold what no sweep writes

def test_compare_on_a_directory_without_points_is_an_error(tmp_path, capsys):
    from postprocess.__main__ import main
    assert main(["compare", str(tmp_path)]) == 2
    assert "no sweep points here" in capsys.readouterr().err


def left_out_of_a_sweep(tmp_path, scene, point_json, name="kn200000"):
    """What analyse leaves out of a sweep holding one completed synthetic point, in the
    directory <scene>/<name>."""
    from postprocess.study import analyse
    (tmp_path / scene / name).mkdir(parents=True)
    point = write_point(tmp_path / scene / name)
    (point / "point.json").write_text(point_json)
    completed(point)
    return point, analyse(tmp_path)[1]


def test_a_point_of_an_unknown_scene_is_listed_not_dropped(tmp_path):
    point, left_out = left_out_of_a_sweep(tmp_path, "avalanche", "{}")
    assert left_out == [(point, "unknown scene 'avalanche' (expected one of single_disk, "
                                "collisional_flow, frictional_flow, chute_3d)")]


def test_a_broken_point_json_is_named(tmp_path):
    _, left_out = left_out_of_a_sweep(tmp_path, "collisional_flow", "{kn: 5")
    assert "point.json: not valid JSON" in left_out[0][1]


def test_a_point_json_naming_a_variable_twice_is_named(tmp_path):
    """JSON's reader keeps the last of a repeated key, silently (a hand-edited point.json)."""
    point, left_out = left_out_of_a_sweep(tmp_path, "collisional_flow",
                                          '{"kn": 200000, "kn": 100000}')
    assert left_out == [(point, "point.json: kn given twice: which value is meant cannot be "
                                "told")]


@pytest.mark.parametrize("point_json, why", [
    # the deck prints the variables it was given into params.txt (kn 200000 here): a point.json
    # that says otherwise is of another run, which would be grouped by point.json and averaged
    # with params.txt's values
    ('{"kn": 100000, "scene": "collisional_flow"}',
     "point.json gives kn = 100000, but params.txt gives 200000.0: they disagree (the outputs "
     "of another run, or an edited file?)"),
    # a run's identity is its point.json, and the runner names its directory after it: a
    # directory whose name says another k_n would report one run's values under another's name
    ('{"kn": 200000, "scene": "collisional_flow"}',
     "point.json gives the run collisional_flow/kn200000, but its directory names it "
     "collisional_flow/kn100000: they disagree (renamed, or the variables of another run?)")])
def test_a_run_whose_identities_disagree_is_named(tmp_path, point_json, why):
    point, left_out = left_out_of_a_sweep(tmp_path, "collisional_flow", point_json,
                                          name="kn100000")
    assert left_out == [(point, why)]


def test_a_point_json_without_its_scene_is_named(tmp_path):
    point, left_out = left_out_of_a_sweep(tmp_path, "collisional_flow", '{"kn": 200000}')
    assert left_out == [(point, "point.json: no scene (the sweep runner writes each point's)")]


def test_a_list_valued_variable_is_named(tmp_path):
    """point.json's variables group the runs: a list there raised TypeError (unhashable)."""
    point, left_out = left_out_of_a_sweep(tmp_path, "collisional_flow", '{"kn": [1, 2]}')
    assert left_out == [(point, "point.json: variable kn is [1, 2], not a number or a word")]


@pytest.mark.parametrize("name,value", [("kn", "0"), ("tau_c", "fast"), ("dt", "-0.001")])
def test_params_that_are_not_positive_numbers_are_refused(tmp_path, name, value):
    point = write_point(tmp_path)
    lines = [f"{name} {value}" if line.split()[0] == name else line
             for line in (point / "params.txt").read_text().splitlines()]
    (point / "params.txt").write_text("\n".join(lines) + "\n")
    with pytest.raises(DataError, match=f"{name} = .* must be a finite number > 0"):
        point_observables(point)


def test_a_run_that_came_to_rest_has_no_steady_motion_to_average(tmp_path):
    """A single disk trapped between bumps (E = 0 from t = 60 on, far longer than REST_TIME):
    averaging it would report a rolling disk's observables for a disk at rest."""
    point = write_point(tmp_path, scene="single_disk")
    lines = (point / "energy.txt").read_text().splitlines()
    for k, line in enumerate(lines):
        words = line.split()
        if not line.startswith("#") and int(words[0]) * 0.001 >= 60:
            lines[k] = " ".join([words[0], "0", "0", "0"] + words[4:])
    (point / "energy.txt").write_text("\n".join(lines) + "\n")
    with pytest.raises(DataError, match="came to rest at t = 60"):
        point_observables(point)


# ---- points the report cannot use are each a 'left out: why' line

def sweep_of(tmp_path, points):
    """A sweep directory of synthetic points: {(scene, kn): writer(point directory)}; each
    point gets, as the runner makes it, the directory <scene>/kn<kn>_seed1 and point.json
    saying so, the same kn in its params.txt if its writer writes one, and the files of a
    completed run (done.txt and timing.json) unless its writer removes them."""
    for (scene, kn), write in points.items():
        point = tmp_path / scene / f"kn{kn}_seed1"
        point.mkdir(parents=True)
        (point / "point.json").write_text(f'{{"kn": {kn}, "scene": "{scene}", "seed": 1}}')
        completed(point)
        write(point)
        params = point / "params.txt"
        if params.exists():
            params.write_bytes(params.read_bytes().replace(b"kn 200000\n", f"kn {kn}\n".encode()))
    return tmp_path


def keep_data_rows(point, keep):
    """energy.txt with only the data rows that keep(row index, number of rows) accepts."""
    lines = (point / "energy.txt").read_text().splitlines()
    data = [l for l in lines if not l.startswith("#")]
    (point / "energy.txt").write_text("\n".join(
        [l for l in lines if l.startswith("#")] +
        [l for k, l in enumerate(data) if keep(k, len(data))]) + "\n")


def single_disk_trajectory(point, end, spacing=0.5):
    rows = [f"{t:g} {t:g} 0.5 1.0 {np.sin(t):g}" for t in np.arange(0, end + 1e-9, spacing)]
    (point / "trajectory.txt").write_text("# time x y vx vy\n" + "\n".join(rows) + "\n")


def test_an_energy_file_with_one_data_row_is_left_out_by_name(tmp_path):
    """A run killed right after its first output line (it raised IndexError)."""
    from postprocess.study import analyse
    sweep = sweep_of(tmp_path, {("collisional_flow", 2): lambda p: keep_data_rows(
        write_point(p), lambda k, n: k == n - 1)})
    (point, reason), = analyse(sweep)[1]
    assert reason == "energy.txt: 1 data row, the analysis needs at least 2: truncated?"


def test_a_single_disk_run_ending_soon_after_average_start_is_left_out_by_name(tmp_path):
    """Two v_y samples after average_start: no period can be found (it raised ValueError)."""
    from postprocess.study import analyse

    def short(point):
        write_point(point, scene="single_disk", run_time=21.0)
        single_disk_trajectory(point, 21.0)
    (point, reason), = analyse(sweep_of(tmp_path, {("single_disk", 2): short}))[1]
    assert reason == ("trajectory.txt: 2 samples after average_start 20, the v_y period needs "
                      "at least 4")


def test_a_broken_point_json_beside_a_usable_point_is_a_left_out_line(tmp_path, capsys):
    """The report draws the usable point's series and lists the broken one (the DataError of
    the broken point.json escaped the figures)."""
    from postprocess.__main__ import main

    def broken(point):
        write_point(point)
        (point / "point.json").write_text("{kn: 5")
    sweep = sweep_of(tmp_path, {("collisional_flow", 2): write_point,
                                ("collisional_flow", 3): broken})
    assert main(["report", str(sweep)]) == 0
    err = capsys.readouterr().err
    assert f"left out {sweep / 'collisional_flow' / 'kn3_seed1'}: point.json: not valid JSON" in err
    assert "\n| 2 | 0.5999 " in (sweep / "report" / "report.md").read_text()   # the usable point's row (kn 2)


def test_a_profile_that_cannot_be_read_is_listed_not_dropped(tmp_path):
    """The report draws the profiles it can read and lists the one it cannot, saying why (it
    was dropped silently)."""
    from postprocess.__main__ import main
    sweep = sweep_of(tmp_path, {
        ("collisional_flow", 2): lambda p: write_profile(write_point(p)),
        ("collisional_flow", 3): lambda p: write_profile(write_point(p), PROFILE_BINS[:2])})
    assert main(["report", str(sweep)]) == 0
    report = (sweep / "report" / "report.md").read_text()
    assert "![profiles](profiles_collisional_flow.png)" in report
    assert (f"- figure profiles_collisional_flow.png: {sweep / 'collisional_flow' / 'kn3_seed1'}/"
            "profile.txt: 2 bins, the header says 3: truncated?") in report


def test_the_report_reads_each_file_of_a_point_once(tmp_path, monkeypatch):
    """A point is loaded once: the E(t) and v_y(t) figures take energy.txt and trajectory.txt
    from the run's record (they read them again)."""
    from postprocess.__main__ import main

    def disk(point):
        write_point(point, scene="single_disk")
        single_disk_trajectory(point, 100.0)
    sweep = sweep_of(tmp_path, {("single_disk", 2): disk, ("single_disk", 3): disk})
    reads, read_text = [], Path.read_text
    monkeypatch.setattr(Path, "read_text",
                        lambda self, *a, **k: reads.append(self) or read_text(self, *a, **k))
    assert main(["report", str(sweep)]) == 0
    assert "![v_y(t) at the softest and the stiffest point]" in \
        (sweep / "report" / "report.md").read_text()
    counts = Counter(p.relative_to(sweep) for p in reads if sweep / "single_disk" in p.parents)
    assert Path("single_disk/kn2_seed1/trajectory.txt") in counts
    # energy.txt twice in its one reading: its header names the columns, then its table
    assert all(n == (2 if p.name == "energy.txt" else 1) for p, n in counts.items()), counts


def crashed(point):
    """A point whose lmp stopped with an error: the sweep runner's failed.txt, no done.txt."""
    write_point(point)
    (point / "done.txt").unlink()
    (point / "failed.txt").write_text("exit status 1\n--- output\nLAMMPS (29 Sep 2021)\n"
                                      "ERROR: Lost atoms: original 4 current 3 (x.cpp:1)\n")


def test_a_crashed_point_is_reported_as_crashed(tmp_path):
    from postprocess.study import analyse
    sweep = sweep_of(tmp_path, {("collisional_flow", 2): crashed,
                                ("collisional_flow", 3): lambda p: (p / "done.txt").unlink()})
    left_out = dict(analyse(sweep)[1])
    assert left_out[sweep / "collisional_flow" / "kn2_seed1"] == (
        "crashed (exit status 1; ERROR: Lost atoms: original 4 current 3 (x.cpp:1); "
        "see failed.txt)")
    assert left_out[sweep / "collisional_flow" / "kn3_seed1"] == "did not complete (no done.txt and timing.json of one run)"


def test_compare_fails_when_nothing_could_be_evaluated(tmp_path, capsys):
    from postprocess.__main__ import main
    from postprocess.reference import load_claims
    sweep = sweep_of(tmp_path, {("collisional_flow", 2): crashed})
    assert main(["compare", str(sweep)]) == 1
    assert (f"comparison: 0 pass, 0 differ from the paper, 0 FAIL, {len(load_claims())} not "
            "evaluated: nothing could be evaluated") in capsys.readouterr().out


def test_the_report_fits_each_series_stiffness_exponents():
    # a series with N_c ~ k_n^0.3 that bends to k_n^0.1 over its stiffest three k_n, and an
    # estimate that crosses zero (no power law): the exponents found, the crossing said
    from postprocess.quantities import EXPONENTS
    from postprocess.write_report import exponent_lines
    kn = 1e4 * 4.0 ** np.arange(6)
    n_c = np.where(kn <= kn[3], kn ** 0.3, kn[3] ** 0.3 * (kn / kn[3]) ** 0.1)
    rows = [dict({q: 1.0 for q in EXPONENTS}, kn=k, label="", N_c=n, mc_c=m)
            for k, n, m in zip(kn, n_c, (0.01, 0.005, 0.002, -1e-4, 1e-5, 2e-5))]
    lines = exponent_lines(rows)
    n_c_line = next(line for line in lines if line.startswith("| N_c |"))
    all_kn, stiff = (float(cell.split("±")[0]) for cell in n_c_line.split("|")[2:4])
    assert 0.15 < all_kn < 0.28      # between the two slopes: the bend is averaged over
    assert stiff == pytest.approx(0.1, abs=1e-9)
    assert "| mc_c | n/a (a value <= 0) | n/a (a value <= 0) |" in lines
    assert "| E_total | 0 ± 0 | 0 ± 0 |" in lines    # flat: exponent 0
    # fewer k_n than the stiff end's fit needs: no table
    assert exponent_lines(rows[:2]) == []


@pytest.mark.parametrize("name", ["energy.txt", "params.txt", "counts.txt", "stopped.txt"])
def test_a_byte_that_is_not_text_is_named_by_file_and_line(tmp_path, capsys, name):
    """A damaged file with a byte that is not UTF-8 (it raised UnicodeDecodeError in the
    report and in summarize): the point is left out, its file and line named."""
    import json
    from postprocess.__main__ import main
    line = 1 if name == "stopped.txt" else 2

    def damaged(point):
        write_point(point)
        path = point / name
        if name == "stopped.txt":
            path.write_text("stopped_at 50\n")
        lines = path.read_bytes().splitlines(keepends=True)
        lines[line - 1] = lines[line - 1][:3] + b"\xff" + lines[line - 1][3:]
        path.write_bytes(b"".join(lines))
    sweep = sweep_of(tmp_path / "results", {("collisional_flow", 2): write_point,
                                            ("collisional_flow", 3): damaged})
    said = f"{name}:{line}: byte 0xff is not UTF-8 text: a damaged or binary file?"
    assert main(["report", str(sweep)]) == 0
    assert f"left out {sweep / 'collisional_flow' / 'kn3_seed1'}: {said}" in capsys.readouterr().err
    assert main(["summarize", str(sweep), "--to", str(tmp_path / "data")]) == 0
    summary = json.loads((tmp_path / "data" / "collisional_flow" / "kn3_seed1.json").read_text())
    assert said in (summary["reason"] or summary["measured"]["problem"])


@pytest.mark.parametrize("command,option", [("report", "--output"), ("limit", "--output"),
                                            ("transition", "--output"), ("summarize", "--to")])
@pytest.mark.parametrize("below", [False, True])
def test_an_output_directory_that_is_a_file_is_refused(tmp_path, capsys, command, option,
                                                       below):
    """--output or --to naming a file, or a directory below one (FileExistsError,
    NotADirectoryError tracebacks): refused before any analysis, exit status 2."""
    from postprocess.__main__ import main
    sweep = sweep_of(tmp_path / "results", {("collisional_flow", 2): write_point})
    (tmp_path / "file").write_text("mine\n")
    out = tmp_path / "file" / "sub" if below else tmp_path / "file"
    assert main([command, str(sweep), option, str(out)]) == 2
    assert (f"postprocess: {option} {out}: {tmp_path / 'file'} is a file, not a directory"
            in capsys.readouterr().err)
    assert (tmp_path / "file").read_text() == "mine\n"
