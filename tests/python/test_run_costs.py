"""scripts/studies/run_costs.py: a sweep's cost per step and atom-step, and the runs whose
recorded CPU is a resumed run's last part alone."""
from pathlib import Path

import pytest

from postprocess.record import RunRecord
from scripts.studies.run_costs import costs


def record(name, cpu, ended="flowing", kn=1e6, dt=1e-3, stopped_at=None, atoms=100):
    """A completed run of run_time 100 (1e5 steps at dt 1e-3) that recorded cpu seconds."""
    return RunRecord(point=Path(name), scene="frictional_flow", source="summary", ended=ended,
                     stopped_at=stopped_at, cpu_seconds=cpu,
                     params={"run_time": "100", "dt": str(dt), "n_mobile": str(atoms),
                             "kn": str(kn)})


def test_a_run_counted_short_is_found_and_what_it_lacks_is_its_groups_rate():
    # five whole runs at 1e-8 s per atom-step (1e5 steps x 100 atoms: 100 s), one resumed run
    # whose last part alone cost 20 s, and a pile that stopped at t = 10 (10 s: a tenth of the
    # steps, not short); a group at another k_n keeps its own rate
    runs = [record(f"w{i}", 100.0 * (1 + 0.05 * (i - 2))) for i in range(5)]
    runs += [record("resumed", 20.0), record("stopped", 10.0, "stopped", stopped_at=10.0)]
    runs += [record(f"stiff{i}", 400.0, kn=1e8, dt=2.5e-4) for i in range(3)]
    groups, short = costs(runs)
    assert sorted(k[-1] for k in groups) == [1e6, 1e8]
    (found, ratio, missing), = short
    assert found.point == Path("resumed")
    # the short run is left out of the median it is judged by (with it: 97.5 s, 77.5 lacking)
    assert ratio == pytest.approx(0.2) and missing == pytest.approx(80.0)
    assert costs(runs, short=0.19)[1] == []


def test_a_group_of_too_few_whole_runs_judges_none():
    runs = [record("a", 100.0), record("b", 20.0)]
    assert costs(runs)[1] == []


def test_an_event_driven_run_has_no_steps_to_cost():
    runs = [record(f"w{i}", 100.0) for i in range(3)] + [record("event", 1.0)]
    runs[-1].variables = {"engine": "event_driven"}
    groups, short = costs(runs)
    assert [len(m) for m in groups.values()] == [3] and short == []
