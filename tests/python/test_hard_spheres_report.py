"""The frictional rule 3 table of scripts/studies/hard_spheres_report.py on synthetic runs: only
event-driven runs that reached run_time are averaged, the soft side is the main series of the
same tangential law over the same window, and one usable run has no error bar."""
from pathlib import Path
from types import SimpleNamespace

from postprocess.selection import Selection
from scripts.studies import hard_spheres_report

SCENE = "frictional_flow"


def window(n_w, energy):
    return {"problem": None, "window": {"blocks": {"N_w": [n_w] * 5, "E_total": [energy] * 5}}}


def hard_run(data, kn, seed, end, n_w, energy=1.0, tc_fraction=0.5):
    """An event-driven run whose measured window is readable whatever ended it, with the
    engine's summary.txt beside it: only `end` tells a run that reached run_time."""
    point = data / SCENE / f"kn{kn:g}_seed{seed}.json"
    summary = data / "event_driven" / SCENE / (point.stem + ".summary.txt")
    summary.parent.mkdir(parents=True, exist_ok=True)
    summary.write_text(f"end {end}\ntc_fraction {tc_fraction}\n")
    return SimpleNamespace(scene=SCENE, point=point, source="summary", ended="flowing",
                           measured=window(n_w, energy),
                           params={"kn": kn, "tc_time": 1e-4, "tangential": "literal"},
                           variables={"kn": kn, "seed": seed, "engine": "event_driven"})


def soft_run(kn, seed, n_w, ended="flowing", tangential="literal", dt_fraction=0.05,
             selected=True):
    variables = {"kn": kn, "seed": seed, "dt_fraction": dt_fraction}
    if tangential != "literal":
        variables["tangential"] = tangential
    measured = (window(n_w, 0.7) if ended == "flowing"
                else {"problem": "the pile stopped before the averaging span"})
    observables = ({"N_w": n_w, "mc_c": 0.25, "t_c": 1.0}
                   if selected and ended == "flowing" else None)
    return SimpleNamespace(scene=SCENE, ended=ended, measured=measured, observables=observables,
                           params={"kn": kn, "tangential": tangential}, variables=variables)


def table(tmp_path, monkeypatch, capsys, hard, soft):
    """The tc command's printed rows, {k_n: {column: cell}}, and its closing line."""
    data, soft_dir = tmp_path / "hard", tmp_path / "soft"
    monkeypatch.setattr(hard_spheres_report, "load_runs",
                        lambda source, selection=Selection(): hard if source == data else soft)
    hard_spheres_report.tc(data, soft_dir)
    lines = capsys.readouterr().out.splitlines()
    rows = [line for line in lines if line.startswith("| ") and not line.startswith("| k_n")]
    header = [c.strip() for c in next(l for l in lines if l.startswith("| k_n")).split("|")[1:-1]]
    cells = [dict(zip(header, (c.strip() for c in row.split("|")[1:-1]))) for row in rows]
    return {float(c["k_n"]): c for c in cells}, lines[-1]


def test_capped_and_collapsed_runs_are_counted_but_never_averaged(tmp_path, monkeypatch, capsys):
    data = tmp_path / "hard"
    hard = [hard_run(data, 1e6, 1, "time", 10.0), hard_run(data, 1e6, 2, "time", 20.0),
            hard_run(data, 1e6, 3, "events", 1e4), hard_run(data, 1e9, 1, "collapse", 1e4),
            hard_run(data, 1e9, 2, "events", 1e4)]
    rows, closing = table(tmp_path, monkeypatch, capsys, hard, [soft_run(1e6, 1, 5.0)])
    assert rows[1e6]["runs"] == "3" and rows[1e6]["reached run_time"] == "2"
    mean, error = rows[1e6]["N_w hard"].split(" +- ")
    assert float(mean) == 15.0 and float(error) == 5.0
    assert rows[1e9]["reached run_time"] == "0" and rows[1e9]["N_w hard"] == "-"
    assert "1 ended by a collapse" in closing and "2 ended by the cap on events" in closing


def test_one_usable_run_has_no_error_bar(tmp_path, monkeypatch, capsys):
    data = tmp_path / "hard"
    hard = [hard_run(data, 1e6, 1, "time", 10.0), hard_run(data, 1e6, 2, "collapse", 30.0)]
    rows, _ = table(tmp_path, monkeypatch, capsys, hard, [])
    assert rows[1e6]["N_w hard"] == "10 +- n/a"
    assert rows[1e6]["soft runs to run_time"] == "0" and rows[1e6]["N_w soft"] == "-"


def test_the_soft_side_is_the_main_series_of_the_same_law_flowing_to_run_time(
        tmp_path, monkeypatch, capsys):
    data = tmp_path / "hard"
    hard = [hard_run(data, kn, 1, "time", 10.0) for kn in (1e6, 1e9)]
    soft = ([soft_run(kn, s, 5.0 + s) for kn in (1e6, 1e7, 1e9) for s in (1, 2)]
            + [soft_run(1e6, 3, 0.0, ended="stopped"),
               soft_run(1e6, 4, 100.0, selected=False),
               soft_run(1e6, 5, 1e3, tangential="cutback"),
               soft_run(1e9, 6, 1e3, dt_fraction=0.025)])
    rows, closing = table(tmp_path, monkeypatch, capsys, hard, soft)
    # the stopped run is in neither average; the one without a selected part only in the window's
    assert rows[1e6]["soft runs to run_time"] == "3" and rows[1e6]["soft runs selected"] == "2"
    assert float(rows[1e6]["N_w soft, selected"].split(" +- ")[0]) == 6.5
    # neither the other tangential law nor a step check at one k_n is mixed in
    assert rows[1e9]["soft runs to run_time"] == "2"
    assert float(rows[1e9]["N_w soft"].split(" +- ")[0]) == 6.5
    assert "dt_fraction 0.05" in closing and "tangential literal" in closing


def test_the_first_and_last_blocks_of_the_hard_runs_show_a_flow_that_does_not_settle(
        tmp_path, monkeypatch, capsys):
    """E over the window's first and last blocks, their range over the runs that reached
    run_time (a capped run's blocks are not among them): a pile that accelerates shows it
    there, where the window's mean hides it."""
    data = tmp_path / "hard"
    hard = [hard_run(data, 1e6, 1, "time", 10.0), hard_run(data, 1e6, 2, "time", 10.0),
            hard_run(data, 1e6, 3, "events", 10.0)]
    for r, scale in zip(hard, (1.0, 1.1, 100.0)):
        r.measured["window"]["blocks"]["E_total"] = [scale * e for e in
                                                          (200, 500, 900, 1400, 2100)]
    monkeypatch.setattr(hard_spheres_report, "load_runs",
                        lambda source, selection=Selection(): hard if source == data else [])
    hard_spheres_report.tc(data, tmp_path / "soft")
    out = capsys.readouterr().out
    assert ("k_n 1e+06: E hard over the window's first and last blocks (of 5) 200-220 and "
            "2100-2310 (2 runs to run_time)") in out
