"""postprocess on synthetic outputs with known answers."""
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from postprocess.io import DataError, numeric_table, read_counts, read_energy, read_params  # noqa
from postprocess.observables import point_observables, span_rates  # noqa: E402
from postprocess.selection import select_steady, steady_spans  # noqa: E402
from postprocess.signals import dominant_period, trend  # noqa: E402

RNG = np.random.default_rng(7)


def wiggle(n, width):
    """Bounded fluctuation of total width just under `width`."""
    return 0.49 * width * np.sin(np.arange(n) * 0.7) * RNG.uniform(0.5, 1.0, n)


# ---- the steady-state selection (SPEC section 5), hand-worked cases

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

def write_point(tmp_path, scene="collisional_flow", n=4, run_time=100.0, average_start=20.0,
                dt=0.001, e_level=0.6, truncate=False):
    tau_c, tau_w = 0.005, 0.007
    (tmp_path / "params.txt").write_text(
        f"scene {scene}\nkn 200000\ne 0.7\nbeta 0.7\nmu 0.5\nsin_theta 0.2\nintegrator verlet\n"
        f"dt {dt}\ntau_c {tau_c}\ntau_w {tau_w}\nseed 1\nrun_time {run_time}\n"
        f"average_start {average_start}\nn_mobile {n}\n")
    lines = ["# energy", "# columns"]
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
    ("no params", "params.txt: missing"),
    ("short run", "before run_time"),
    ("counts", "atoms, the header says"),
    ("nan", "non-finite"),
    ("word", "not a number"),
])
def test_broken_outputs_name_the_file_and_the_problem(tmp_path, damage, message):
    point = write_point(tmp_path, truncate=(damage == "truncate"))
    if damage == "no params":
        (point / "params.txt").unlink()
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


def test_trend_of_noise_and_of_a_ramp():
    t = np.arange(0, 1000, 1.0)
    noise = RNG.normal(0, 1, len(t))
    slope, error = trend(t, noise, 0, 1000)
    assert abs(slope) < 4 * error
    slope, error = trend(t, noise + 0.01 * t, 0, 1000)
    assert slope == pytest.approx(0.01, abs=4 * error)


@pytest.mark.parametrize("damage,message", [
    ("word", r"profile.txt:\d+: not a number"),
    ("short", "does not have 6 columns"),
    ("missing bin", "bins, the header says 3: truncated"),
])
def test_broken_profile_names_the_file_and_the_problem(tmp_path, damage, message):
    from postprocess.io import read_profile
    bins = ["1 0.125 2 0.5 0.1 0.0", "2 0.375 1 0.25 0.2 0.0", "3 0.625 0 0 0 0"]
    if damage == "word":
        bins[1] = bins[1].replace("0.25", "x.25")
    if damage == "short":
        bins[1] = "2 0.375 1"
    if damage == "missing bin":
        bins = bins[:2]
    (tmp_path / "profile.txt").write_text("# fix ave/chunk\n# header\n# columns\n1000 3 3\n" +
                                          "\n".join(bins) + "\n")
    with pytest.raises(DataError, match=message):
        read_profile(tmp_path)


def test_broken_contact_rows_name_the_line(tmp_path):
    from postprocess.io import read_rows
    (tmp_path / "contacts.txt").write_text(
        "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ENTRIES\n1\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n"
        "0 1\nITEM: ENTRIES c_1 c_2\n1 2 1 0.1 0.005 -1 0.7 nan?\n")
    with pytest.raises(DataError, match=r"contacts.txt:10: not a number"):
        read_rows(tmp_path)
