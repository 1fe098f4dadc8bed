"""Contact rows through the analysis (postprocess/durations.py): a real sweep of the 3D chute
with rows, whose rows and counters must tell the same time with two or more contacts; P(tau)
and that split kept in the summaries, so that the report from the summaries has the same
contact table as the report from the raw outputs."""
import numpy as np
import pytest

from postprocess.__main__ import main
from postprocess.durations import DURATION_EDGES, TAIL_CUT
from postprocess.runs import load_runs
from test_sweep import sweep

# dt = dt_cap = 1e-3 exactly: average_start = 6 falls on a line of energy.txt, the line written
# at the counters' restart, which still holds the sums from before it (the case where a split
# that takes the counters from that line is wrong by a factor ~3). At k_n = 8e4, dt is
# tau_c/10 and no line falls on the restart.
TINY = """
name = "rows"
[defaults]
scene = "chute_3d"
kn = [2e4, 8e4]
dt_fraction = 0.1
dt_cap = 1e-3
spheres = 60
length = 5
width = 5
sin_theta = 0.40
run_time = 12
average_start = 6
rows = "yes"
rows_time = 4
[[grid]]
seed = 1
"""


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    where = tmp_path_factory.mktemp("rows")
    config = where / "rows.toml"
    config.write_text(TINY)
    sweep(config, where / "results")
    return where / "results"


def test_rows_keep_every_digit_of_their_times(results):
    # a contact starts and ends at a step: its start and end are whole numbers of steps since
    # the run's start (the fix's clock), to round-off; rows written with dump local's default
    # %g (6 digits) are off by up to 0.006 steps here (t ~ 8, dt 7.9e-4), and by tens of steps
    # at stiff k_n, where a pair's successive contacts then overlap
    for record in load_runs(results):
        rows, dt = record.outputs.rows, record.params["dt"]
        for times in (rows["start"] / dt, (rows["start"] + rows["duration"]) / dt):
            assert np.max(np.abs(times - np.round(times))) < 1e-6
        # no pair has two contacts at once
        key = rows["id_i"] * 1e6 + rows["id_j"]
        order = np.lexsort((rows["start"], key))
        start, end = rows["start"][order], (rows["start"] + rows["duration"])[order]
        same = key[order][1:] == key[order][:-1]
        assert np.all(start[1:][same] >= end[:-1][same] - 0.5 * dt)


def test_rows_and_counters_tell_the_same_time_with_two_or_more_contacts(results):
    records = load_runs(results)
    assert len(records) == 2
    for record in records:
        split = record.measured["contacts"]["split"]
        for lasting in ("3", "10"):
            s = split[lasting]
            # the counters' window starts one energy.txt line (0.1 of the 3.5-unit window)
            # after the rows' and contacts longer than the window have no row (unseen): 10 %
            # covers both; reading the counters at the restart's line is off by a factor ~3
            assert s["t_multiple_rows"] == pytest.approx(s["t_multiple_counters"], rel=0.1)
            assert s["lasting"] + s["bursts"] == pytest.approx(s["t_multiple_rows"])
        # a lower threshold calls more of the time lasting
        assert split["3"]["lasting"] >= split["10"]["lasting"]


def test_the_histogram_holds_every_contact_that_ended_in_the_window(results):
    for record in load_runs(results):
        contacts = record.measured["contacts"]
        rows = record.outputs.rows
        tau = {"disk": record.params["tau_c"], "boundary": record.params["tau_w"]}
        for code, kind in ((1, "disk"), (2, "boundary")):
            ended = (rows["kind"] == code) & (rows["start"] + rows["duration"] >=
                                              record.params["average_start"])
            assert contacts["contacts"][kind] == np.count_nonzero(ended) > 100
            scaled = rows["duration"][ended] / tau[kind]
            # no contact is shorter than a tenth of a binary one or longer than the bins
            assert sum(contacts["histogram"][kind]) == contacts["contacts"][kind]
            assert contacts["tail"][kind] == np.count_nonzero(scaled > TAIL_CUT)
            assert scaled.min() > DURATION_EDGES[0]


def test_report_from_summaries_has_the_contact_table_of_the_raw_report(results, tmp_path):
    data = tmp_path / "data"
    assert main(["summarize", str(results), "--to", str(data)]) == 0
    texts = []
    for source, out in ((results, tmp_path / "raw"), (data, tmp_path / "summaries")):
        assert main(["report", str(source), "--output", str(out)]) == 0
        text = (out / "report.md").read_text()
        assert (out / "durations_chute_3d.png").stat().st_size > 10000
        texts.append(text[text.index("### Contact durations"):text.index("\n- ")])
    assert texts[0] == texts[1]
    assert "sphere-sphere contacts" in texts[0] and "lasting (> 3 tau)" in texts[0]
