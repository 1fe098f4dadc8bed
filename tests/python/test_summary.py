"""Run summaries (python3 -m postprocess summarize, docs/sweeps.md): the report and compare
from summaries give the tables they give from the raw outputs; a summary that is not one, or
of another version, is refused by name."""
import csv
import json

import numpy as np
import pytest

from postprocess.__main__ import main
from postprocess.rundir import run_name
from postprocess.runs import load_runs
from postprocess.selection import Selection
from test_postprocess import completed, crashed, single_disk_trajectory, write_point

RNG = np.random.default_rng(11)


def with_energy(point, energy, dt=0.001, stop=None):
    """Replace e_total (and e_trans, e_rot: 0.9 and 0.1 of it) by energy(t); with `stop`, end
    the run there as the deck does when the pile stops."""
    lines = []
    for line in (point / "energy.txt").read_text().splitlines():
        if not line.startswith("#"):
            words = line.split()
            t = int(words[0]) * dt
            if stop is not None and t > stop:
                continue
            e = energy(t)
            line = " ".join([words[0], repr(0.9 * e), repr(0.1 * e), repr(e)] + words[4:])
        lines.append(line)
    (point / "energy.txt").write_text("\n".join(lines) + "\n")
    if stop is not None:
        (point / "stopped.txt").write_text(f"stopped_at {stop}\n")
    return point


def frictional(point, seed, energy=lambda t: 0.6 + 0.01 * np.sin(t), stop=None):
    """A frictional run of 1000 time units, E(t) sampled every 0.1."""
    write_point(point, scene="frictional_flow", run_time=1000.0, average_start=100.0)
    params = point / "params.txt"
    params.write_text(params.read_text().replace("seed 1\n", f"seed {seed}\n"))
    with_energy(point, energy, stop=stop)


def sweep(tmp_path):
    """A synthetic sweep with one run of each kind the report tells apart: usable collisional
    and single-disk points at two k_n, frictional seeds flowing in range (steady at every
    resolution; or kept at 1 and 5 only: samples wider than 0.45), out of range, stopped
    after a steady part and before average_start, a crashed and an unfinished point."""
    out = tmp_path / "results"

    def point(scene, variables):
        """A point's directory as the runner makes it: named by its variables, which its
        point.json holds."""
        variables = {"scene": scene, **variables}
        p = out / run_name(variables)
        p.mkdir(parents=True)
        (p / "point.json").write_text(json.dumps(variables))
        completed(p)
        return p

    for kn in (1e5, 4e5):
        p = write_point(point("collisional_flow", {"kn": kn}))
        p.joinpath("params.txt").write_text(p.joinpath("params.txt").read_text().replace(
            "kn 200000", f"kn {kn:g}"))
        with_energy(p, lambda t, kn=kn: 0.6 * (kn / 1e5) ** -0.05 + 0.01 * np.sin(t))
        p = point("single_disk", {"kn": kn})
        write_point(p, scene="single_disk")
        p.joinpath("params.txt").write_text(p.joinpath("params.txt").read_text().replace(
            "kn 200000", f"kn {kn:g}"))
        single_disk_trajectory(p, 100.0, spacing=0.1)
    noise = RNG.uniform(-0.3, 0.3, 10001)
    frictional(point("frictional_flow", {"kn": 200000, "seed": 1}), 1)
    frictional(point("frictional_flow", {"kn": 200000, "seed": 2}), 2,
               lambda t: 0.65 + noise[int(round(t / 0.1))])
    frictional(point("frictional_flow", {"kn": 200000, "seed": 3}), 3, lambda t: 0.95 + 0.01 * np.sin(t))
    frictional(point("frictional_flow", {"kn": 200000, "seed": 4}), 4, stop=800.0)
    frictional(point("frictional_flow", {"kn": 200000, "seed": 5}), 5, stop=40.0)
    crashed(point("collisional_flow", {"kn": 8e5}))
    (point("collisional_flow", {"kn": 1.6e6}) / "done.txt").unlink()
    return out


def table(path, without=("point",)):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [{k: v for k, v in row.items() if k not in without} for row in rows]


@pytest.fixture(scope="module")
def summarized(tmp_path_factory):
    tmp_path = tmp_path_factory.mktemp("summaries")
    results = sweep(tmp_path)
    assert main(["summarize", str(results), "--to", str(tmp_path / "data")]) == 0
    return results, tmp_path / "data"


@pytest.mark.parametrize("options", [[], ["--energy-range", "0.3", "1.2"],
                                     ["--resolution", "5"], ["--resolution", "0.1"]])
def test_the_report_from_summaries_has_the_tables_of_the_report_from_raw_outputs(
        summarized, tmp_path, capsys, options):
    results, data = summarized
    assert main(["report", str(results), "--output", str(tmp_path / "raw")] + options) == 0
    raw_said = capsys.readouterr().err
    assert main(["report", str(data), "--output", str(tmp_path / "summary")] + options) == 0
    summary_said = capsys.readouterr().err
    for name in ("observables_collisional_flow.csv", "observables_single_disk.csv",
                 "observables_frictional_flow.csv", "runs.csv", "comparison.csv"):
        raw = table(tmp_path / "raw" / name)
        assert raw and raw == table(tmp_path / "summary" / name), name
    # the same runs left out, for the same reasons
    assert raw_said.count("left out") == summary_said.count("left out") >= 3
    for line in raw_said.splitlines():
        point, reason = line.removeprefix(f"left out {results}/").split(": ", 1)
        assert f"left out {data}/{point}.json: {reason}" in summary_said
    assert "crashed (exit status 1; ERROR: Lost atoms" in summary_said


def test_several_directories_are_one_sweep(summarized, tmp_path):
    # a preset and its extension (data/chute_3d and data/chute_3d_stiff): the summaries split
    # in two directories, by run, give the tables of one directory holding all of them
    import shutil
    _, data = summarized
    paths = sorted(data.glob("*/*.json"))
    for k, path in enumerate(paths):
        target = tmp_path / ("first" if k % 2 else "second") / path.parent.name / path.name
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(path, target)
    assert main(["report", str(data), "--output", str(tmp_path / "one")]) == 0
    assert main(["report", str(tmp_path / "first"), str(tmp_path / "second"), "--output",
                 str(tmp_path / "two")]) == 0
    for name in ("observables_collisional_flow.csv", "observables_single_disk.csv",
                 "observables_frictional_flow.csv", "comparison.csv"):
        assert table(tmp_path / "one" / name) == table(tmp_path / "two" / name), name
    text = (tmp_path / "two" / "report.md").read_text()
    assert f"{tmp_path / 'first'} + {tmp_path / 'second'}" in text.splitlines()[0]
    with pytest.raises(SystemExit):
        main(["summarize", str(tmp_path / "first"), str(tmp_path / "second")])


def test_summaries_say_how_each_run_ended_and_what_it_is(summarized):
    results, data = summarized
    raw = {r.point.relative_to(results): r for r in load_runs(results)}
    summaries = {r.point.relative_to(data).with_suffix(""): r for r in load_runs(data)}
    assert raw.keys() == summaries.keys()
    ended = {str(k): r.ended for k, r in summaries.items()}
    assert ended["collisional_flow/kn800000"] == "failed"
    assert ended["collisional_flow/kn1.6e+06"] == "incomplete"
    assert ended["frictional_flow/kn200000_seed4"] == ended["frictional_flow/kn200000_seed5"] \
        == "stopped"
    assert ended["frictional_flow/kn200000_seed1"] == "flowing"
    for key, r in raw.items():
        s = summaries[key]
        assert (s.ended, s.stopped_at, s.variables, s.params, s.reason) == \
            (r.ended, r.stopped_at, r.variables, r.params, r.reason)
        assert s.observables == r.observables
    # the frictional seed with wide samples: kept at resolutions 1 and 5, not at 0.1
    noisy = summaries[next(k for k in summaries if str(k) == "frictional_flow/kn200000_seed2")]
    assert noisy.kept(Selection(), (0.1, 1.0, 5.0)) == {0.1: 0, 1.0: 1, 5.0: 1}


def test_a_summary_is_a_few_kilobytes(summarized):
    """A frictional run of 1000 time units: its E(t) over windows of 1 (1000 values) and its
    steady parts' blocks; far below its raw outputs."""
    _, data = summarized
    sizes = {p.name: p.stat().st_size for p in data.glob("*/*.json")}
    assert max(sizes.values()) < 16000, sizes


def test_a_resolution_the_summaries_do_not_hold_is_refused(summarized, capsys):
    _, data = summarized
    assert main(["compare", str(data), "--resolution", "2"]) == 2
    assert "summaries hold the steady parts at resolutions 0.1, 1, 5 only: resolution 2 " \
           "needs the raw outputs" in capsys.readouterr().err


@pytest.mark.parametrize("damage,message", [
    ("version", "run summary version 2; this code reads version 1"),
    ("not json", "not a run summary: not valid JSON"),
    ("other json", 'not a run summary (no "schema": "granmn-run-summary")'),
    ("block", "corrupt summary: measured.window.blocks.N_c[0] is 'x', not a finite number"),
    ("missing", "corrupt summary: the summary has no params"),
    ("params", "params: tau_c = 'fast' must be a finite number > 0"),
    ("ended", "corrupt summary: ended is 'exploded', not one of flowing, stopped, failed, "
              "incomplete"),
    ("rule", "its steady parts were found with"),
    ("histogram", "corrupt summary: measured.contacts.histogram.disk is not 50 counts"),
    ("tail", "corrupt summary: measured.contacts.tail.boundary is 7, not a count of at most 5"),
    ("contacts", "corrupt summary: measured.contacts.contacts.disk is 2, not a count of at "
                 "least the histogram's 3"),
    ("split", "corrupt summary: measured.contacts.split has the thresholds ['3', 'x'], not "
              "['10', '3']"),
    ("split part", "corrupt summary: measured.contacts.split.10 has no bursts"),
    # hand-edited or damaged values that would be averaged: a negative rate, a span (a
    # seed's weight) of zero or below, a run that did not complete with values
    ("negative rate", "corrupt summary: measured.window.blocks.N_w[2] is -0.5, negative: it is "
                      "an energy, a rate, a time fraction or a count"),
    ("negative energy", "corrupt summary: energy.E[3] is -1, negative"),
    ("zero span", "corrupt summary: measured.window.span is 0, not a time span > 0"),
    ("negative span", "corrupt summary: measured.steady.1[0].span is -500, not a time span > 0"),
    ("failed with values", "corrupt summary: params is there, but the run failed: it has no "
                           "values"),
    ("flowing and stopped", "corrupt summary: stopped_at is there, but the run ended flowing"),
    # what would otherwise raise KeyError, AttributeError or TypeError in the report
    ("unknown scene", "corrupt summary: the summary names an unknown scene 'avalanche' "
                      "(expected one of single_disk, collisional_flow"),
    ("variables null", "corrupt summary: measured is there without variables"),
    ("list variable", "variables: variable kn is [100000, 200000], not a number or a word"),
    # what the raw reader refuses too (io: one rule, one check for both)
    ("huge block", "corrupt summary: measured.window.blocks.E_total[0] is 1e+308, beyond "
                   "1e+150 in magnitude"),
    ("disagreeing params", "corrupt summary: variables gives kn = 100000.0, but params gives "
                           "300000.0: they disagree"),
    ("key twice", "cpu_seconds given twice: which value is meant cannot be told"),
    # a run's identity is its variables (point.json's): the name is derived from them
    ("point", "corrupt summary: point is 'collisional_flow/kn300000', but the file is "
              "collisional_flow/kn100000.json"),
    ("variables of another run", "corrupt summary: variables gives the run "
                                 "collisional_flow/kn300000, but its file names it "
                                 "collisional_flow/kn100000: they disagree"),
])
def test_a_summary_that_is_not_one_is_refused_by_name(summarized, tmp_path, damage, message):
    _, data = summarized
    path = tmp_path / "data" / "collisional_flow" / "kn100000.json"
    original = data / path.parent.name / path.name
    if damage in ("rule", "negative span"):
        path = tmp_path / "data" / "frictional_flow" / "kn200000_seed1.json"
        original = data / "frictional_flow" / "kn200000_seed1.json"
    if damage == "unknown scene":
        path = tmp_path / "data" / "avalanche" / "kn100000.json"
    path.parent.mkdir(parents=True)
    summary = json.loads(original.read_text())
    if damage == "version":
        summary["version"] = 2
    if damage == "other json":
        summary = {"kn": 1}
    if damage == "block":
        summary["measured"]["window"]["blocks"]["N_c"][0] = "x"
    if damage == "missing":
        del summary["params"]
    if damage == "params":
        summary["params"]["tau_c"] = "fast"
    if damage == "ended":
        summary["ended"] = "exploded"
    if damage == "rule":
        summary["steady_rule"]["max_width"] = 0.3
    if damage == "negative rate":
        summary["measured"]["window"]["blocks"]["N_w"][2] = -0.5
    if damage == "negative energy":
        summary["energy"]["E"][3] = -1
    if damage == "zero span":
        summary["measured"]["window"]["span"] = 0
    if damage == "negative span":
        summary["measured"]["steady"]["1"][0]["span"] = -500
    if damage == "failed with values":
        summary.update(ended="failed", failure="exit status 1", reason="crashed")
    if damage == "flowing and stopped":
        summary["stopped_at"] = 50.0
    if damage == "unknown scene":
        summary.update(scene="avalanche", point="avalanche/kn100000")
    if damage == "variables null":
        summary["variables"] = None
    if damage == "list variable":
        summary["variables"]["kn"] = [100000, 200000]
    if damage == "huge block":
        summary["measured"]["window"]["blocks"]["E_total"][0] = 1e308
    if damage == "disagreeing params":
        summary["params"]["kn"] = 300000.0
    if damage == "point":
        summary["point"] = "collisional_flow/kn300000"
    if damage == "variables of another run":
        summary["variables"]["kn"] = summary["params"]["kn"] = 300000.0
    if damage in ("histogram", "tail", "contacts", "split", "split part"):
        # a run with contact rows (durations.run_contacts), damaged
        histogram = [0] * 50
        histogram[20] = 3
        contacts = {"histogram": {"disk": histogram, "boundary": [0] * 50},
                    "contacts": {"disk": 3, "boundary": 5}, "tail": {"disk": 0, "boundary": 0}}
        if damage == "histogram":
            contacts["histogram"]["disk"] = histogram[:-1]
        if damage == "tail":
            contacts["tail"]["boundary"] = 7
        if damage == "contacts":
            contacts["contacts"]["disk"] = 2
        if damage.startswith("split"):
            from postprocess.durations import SPLIT_NAMES
            part = {name: 0.01 for name in SPLIT_NAMES}
            contacts["split"] = {"3": part, "x" if damage == "split" else "10":
                                 {k: v for k, v in part.items() if k != "bursts"}}
        summary["measured"].update(contacts=contacts, contacts_problem=None)
    text = "{kn: 5" if damage == "not json" else json.dumps(summary)
    if damage == "key twice":
        text = text.replace('"cpu_seconds": ', '"cpu_seconds": 5, "cpu_seconds": ')
    path.write_text(text)
    record, = load_runs(tmp_path / "data")
    assert record.ended == "unreadable" and record.reason.startswith(f"{path}: ")
    assert message in record.reason


@pytest.mark.parametrize("value,why", [
    (1e308, "beyond 1e+150 in magnitude, more than any energy, rate, time or count of a run (a "
            "damaged file?)"),
    (-0.5, "negative: it is an energy, a rate, a time fraction or a count"),
    (float("nan"), "not a finite number")])
def test_the_raw_and_the_summary_reader_refuse_a_value_alike(summarized, tmp_path, value, why):
    """An energy of 1e308 in one row of energy.txt (averaged into the report, with numpy's
    warnings only), a negative one, a nan: the raw reader refuses it as the summary reader
    refuses the same value in a summary's E(t), by one rule (io.checked_values), in the same
    words."""
    import shutil
    results, data = summarized
    raw = tmp_path / "results" / "collisional_flow" / "kn100000"
    shutil.copytree(results / "collisional_flow" / "kn100000", raw)
    lines = (raw / "energy.txt").read_text().splitlines()
    row = len(lines) // 2
    words = lines[row].split()
    words[3] = repr(value)
    lines[row] = " ".join(words)
    (raw / "energy.txt").write_text("\n".join(lines) + "\n")
    from_raw, = load_runs(tmp_path / "results")
    assert from_raw.reason == f"energy.txt:{row + 1}: e_total is {value:g}, {why}"

    summary = json.loads((data / "collisional_flow" / "kn100000.json").read_text())
    summary["energy"]["E"][3] = value
    path = tmp_path / "data" / "collisional_flow" / "kn100000.json"
    path.parent.mkdir(parents=True)
    path.write_text(json.dumps(summary))
    from_summary, = load_runs(tmp_path / "data")
    assert from_summary.reason == f"{path}: corrupt summary: energy.E[3] is {value:g}, {why}"


def test_summarize_needs_raw_outputs(summarized, capsys):
    _, data = summarized
    assert main(["summarize", str(data), "--to", str(data / "again")]) == 2
    assert "no sweep points here" in capsys.readouterr().err


@pytest.mark.parametrize("damage", ["unknown scene", "variables null", "list variable"])
def test_the_report_lists_a_summary_it_cannot_group_and_goes_on(summarized, tmp_path, capsys,
                                                                 damage):
    """A summary of an unknown scene, with variables null or a list-valued variable, beside
    usable ones: a 'left out' line naming the file (they raised KeyError, AttributeError and
    TypeError)."""
    import shutil
    _, data = summarized
    shutil.copytree(data, tmp_path / "data")
    path = tmp_path / "data" / "collisional_flow" / "kn100000.json"
    summary = json.loads(path.read_text())
    if damage == "unknown scene":
        path.unlink()
        path = tmp_path / "data" / "avalanche" / "kn100000.json"
        path.parent.mkdir()
        summary.update(scene="avalanche", point="avalanche/kn100000")
    if damage == "variables null":
        summary["variables"] = None
    if damage == "list variable":
        summary["variables"]["kn"] = [100000, 200000]
    path.write_text(json.dumps(summary))
    assert main(["report", str(tmp_path / "data"), "--output", str(tmp_path / "report")]) == 0
    assert f"left out {path}: {path}: corrupt summary" in capsys.readouterr().err


def test_a_summary_with_integer_params_is_read(summarized, tmp_path):
    """JSON integers are numbers: a hand-written params.kn 100000 was refused as 'must be a
    finite number > 0'."""
    _, data = summarized
    path = tmp_path / "data" / "collisional_flow" / "kn100000.json"
    path.parent.mkdir(parents=True)
    summary = json.loads((data / "collisional_flow" / "kn100000.json").read_text())
    assert summary["params"]["kn"] == 100000.0
    summary["params"]["kn"] = 100000
    summary["params"]["n_mobile"] = 4
    path.write_text(json.dumps(summary))
    record, = load_runs(tmp_path / "data")
    original, = [r for r in load_runs(data) if r.point == data / "collisional_flow" /
                 "kn100000.json"]
    assert record.reason is None and record.params == original.params
    assert record.observables == original.observables


def test_a_results_directory_with_its_own_summaries_counts_each_run_once(summarized, tmp_path,
                                                                          capsys):
    """`report results data` (data: the summaries of results) is `report results`: each run
    once, from its raw outputs, and each summary a left-out line naming the run it copies
    (each run was counted twice, the errors across seeds shrinking)."""
    results, data = summarized
    assert main(["report", str(results), "--output", str(tmp_path / "one")]) == 0
    alone = capsys.readouterr().err
    assert main(["report", str(results), str(data), "--output", str(tmp_path / "both")]) == 0
    said = capsys.readouterr().err
    for name in ("observables_collisional_flow.csv", "observables_single_disk.csv",
                 "observables_frictional_flow.csv", "runs.csv", "comparison.csv"):
        assert table(tmp_path / "one" / name) == table(tmp_path / "both" / name), name
    copies = [line for line in said.splitlines() if line not in alone.splitlines()]
    assert len(copies) == len(list(data.glob("*/*.json")))
    for path in data.glob("*/*.json"):
        point = results / path.parent.name / path.stem
        assert f"left out {path}: the same run as {point}: counted once" in copies
    assert f"- `{path}`: the same run as {point}: counted once" in \
        (tmp_path / "both" / "report.md").read_text()


def test_two_different_runs_under_one_name_are_refused(summarized, tmp_path, capsys):
    """A run's summary beside another run of the same point and seed (a rerun, a run on other
    ranks) whose values differ: which to count is the user's choice, not an average of both
    as two seeds."""
    import shutil
    _, data = summarized
    shutil.copytree(data, tmp_path / "other")
    path = tmp_path / "other" / "collisional_flow" / "kn100000.json"
    summary = json.loads(path.read_text())
    summary["measured"]["window"]["blocks"]["N_c"][0] *= 1.1
    path.write_text(json.dumps(summary))
    assert main(["compare", str(data), str(tmp_path / "other")]) == 2
    assert (f"postprocess: {data / 'collisional_flow' / 'kn100000.json'} and {path} are both "
            "the run collisional_flow/kn100000, but their observables differ: two different "
            "runs under one name (analyse them apart)") in capsys.readouterr().err


def test_summarize_keeps_a_complete_summary_rather_than_write_a_less_complete_one(
        summarized, tmp_path, capsys):
    """summarize of a stopped sweep (a point not finished, a point whose energy.txt was cut)
    into a directory of complete summaries overwrote them with the incomplete ones: now each
    is kept and named with what the new one lacks; the others are written; --replace writes
    all."""
    import shutil
    results, data = summarized
    shutil.copytree(results, tmp_path / "results")
    shutil.copytree(data, tmp_path / "data")
    again, to = tmp_path / "results", tmp_path / "data"
    (again / "collisional_flow" / "kn100000" / "done.txt").unlink()    # still running
    keep_rows = again / "collisional_flow" / "kn400000" / "energy.txt"
    lines = keep_rows.read_text().splitlines()
    keep_rows.write_text("\n".join(lines[:len(lines) // 2]) + "\n")      # cut short
    before = {p: p.read_text() for p in to.glob("*/*.json")}
    assert main(["summarize", str(again), "--to", str(to)]) == 0
    out, err = capsys.readouterr()
    unfinished, cut = (to / "collisional_flow" / f"{k}.json" for k in ("kn100000", "kn400000"))
    assert (f"kept {unfinished}: it holds a run that completed (flowing); the new one's did "
            "not complete (no done.txt and timing.json of one run) (--replace writes the new one)") in err
    assert f"kept {cut}: it was measured; the new one's: energy.txt: ends at t = " in err
    assert len(err.splitlines()) == 2
    assert f"summaries: {len(before) - 2} runs written in {to} (" in out
    assert out.rstrip().endswith(", 2 kept as they were")
    assert {p: p.read_text() for p in to.glob("*/*.json")} == before   # the same runs
    assert main(["summarize", str(again), "--to", str(to), "--replace"]) == 0
    assert json.loads(unfinished.read_text())["ended"] == "incomplete"
    assert f"summaries: {len(before)} runs written" in capsys.readouterr().out
    # the finished run's summary replaces the unfinished one's (more complete)
    completed(again / "collisional_flow" / "kn100000")
    assert main(["summarize", str(again), "--to", str(to)]) == 0
    assert json.loads(unfinished.read_text())["ended"] == "flowing"
    assert "kept" not in capsys.readouterr().err


def test_summarize_keeps_a_file_it_cannot_read(summarized, tmp_path, capsys):
    """A file in the way that is not a summary this code reads (another version, damaged) is
    not overwritten without --replace."""
    results, data = summarized
    path = tmp_path / "data" / "collisional_flow" / "kn100000.json"
    path.parent.mkdir(parents=True)
    path.write_text('{"schema": "granmn-run-summary", "version": 2}')
    assert main(["summarize", str(results), "--to", str(tmp_path / "data")]) == 0
    assert f"kept {path}: this code cannot read it ({path}: run summary version 2" in \
        capsys.readouterr().err
    assert json.loads(path.read_text())["version"] == 2
