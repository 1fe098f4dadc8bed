"""Run summaries of a real sweep (docs/sweeps.md): the report from the summaries has the
tables of the report from the raw outputs (runs of every scene, a frictional run with a
steady part, one without, a failed point), and each summary is a few kB."""
import csv

from postprocess.__main__ import main
from test_main_job import TINY as MAIN_JOB_TINY
from test_sweep import sweep

# the main job's tiny sweep, a frictional run long enough to keep a steady part, and a point
# that fails past the deck's dry run (more snapshot steps than LAMMPS counts)
TINY = MAIN_JOB_TINY + """
[[grid]]
scene = "frictional_flow"
kn = [1.25e4]
run_time = 700
seed = 2
dt_fraction = 0.05
dt_cap = 1
average_start = 100
[[grid]]
scene = "collisional_flow"
kn = [1e5]
snapshot_interval = 1e12
"""


def table(path):
    with open(path, newline="") as f:
        return [{k: v for k, v in row.items() if k != "point"} for row in csv.DictReader(f)]


def test_a_real_sweeps_report_from_summaries_matches_the_report_from_its_outputs(tmp_path,
                                                                                capsys):
    config = tmp_path / "tiny.toml"
    config.write_text(TINY)
    results = tmp_path / "results"
    ran = sweep(config, results, check=False)
    assert ran.returncode == 1            # the point past LAMMPS's step count failed, the others ran
    data = tmp_path / "data"
    assert main(["summarize", str(results), "--to", str(data)]) == 0
    sizes = [p.stat().st_size for p in data.glob("*/*.json")]
    # a few kB; the frictional run of 700 time units the most (its E(t): 700 means)
    assert len(sizes) == 7 and max(sizes) < 12000, sizes
    for source, out in ((results, tmp_path / "from_raw"), (data, tmp_path / "from_summaries")):
        assert main(["report", str(source), "--output", str(out)]) == 0
    said = capsys.readouterr().err
    for name in ("observables_single_disk.csv", "observables_collisional_flow.csv",
                 "observables_frictional_flow.csv", "runs.csv", "comparison.csv"):
        raw = table(tmp_path / "from_raw" / name)
        assert raw and raw == table(tmp_path / "from_summaries" / name), name
    # the failed point: crashed, with lmp's error, from both sources
    crashed = [line for line in said.splitlines() if "crashed (exit status 1; ERROR:" in line]
    assert len(crashed) == 2 and "snapshot_interval = 1e+12" in crashed[0], said
    # the frictional run of 700 (seed 2, dt = tau_c/20: ~4 s of CPU) flows with a steady part
    # kept at resolution 1, so observables_frictional_flow.csv above has its row and the
    # selection's path is compared (which seed has one is chance: the trajectory is chaotic,
    # and seed 1 lost its steady part when the decks' integrator became fix nve/disc/mn, the
    # same trajectory to rounding only); the run of 12 time units has no steady
    # part: left out, from both sources
    assert said.count("no steady part with mean energy") == 2
