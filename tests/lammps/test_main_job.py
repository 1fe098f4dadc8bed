"""The main job end to end on a shortened study: sweep, post-processing, figures, comparison,
report (scripts/main.sh --config)."""
import os
import re
import subprocess

from granmn_run import ROOT
from postprocess.reference import load_claims  # noqa: E402

TINY = """
name = "tiny"
[defaults]
run_time = 12
average_start = 2
[[grid]]
scene = "single_disk"
kn = [5e4, 2e5]
[[grid]]
scene = "collisional_flow"
kn = [1.25e4, 5e4]
[[grid]]
scene = "frictional_flow"
kn = [1.25e4]
"""


def test_shortened_main_job_writes_a_report_with_every_figure_and_the_comparison(tmp_path):
    config = tmp_path / "tiny.toml"
    config.write_text(TINY)
    output = tmp_path / "study"
    # against the LAMMPS under test (tests/CMakeLists.txt), whose build main.sh brings up to date
    generation = os.environ.get("GRANMN_LAMMPS_GENERATION", "debian12")
    proc = subprocess.run([str(ROOT / "scripts" / "main.sh"), "--config", str(config),
                           "--output", str(output), "--lammps", generation],
                          capture_output=True, text=True)
    text = proc.stdout + proc.stderr
    assert "requested e = 0.7" in text                     # the demonstration ran
    assert f"report: {output}/report/report.md" in text, text[-3000:]
    assert re.search(r"comparison: \d+ pass, \d+ differ from the paper, \d+ FAIL, \d+ not "
                     r"evaluated", text)
    report = (output / "report" / "report.md").read_text()
    figures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", report)
    expected = {f"{kind}_{scene}.png" for scene in ("single_disk", "collisional_flow")
                for kind in ("stiffness", "profiles", "energy", "snapshot")}
    expected |= {"vy_single_disk.png", "energy_frictional_flow.png",
                 "snapshot_frictional_flow.png"}
    assert expected <= set(figures)
    for name in figures:
        assert (output / "report" / name).stat().st_size > 10000    # a real plot
    for claim in load_claims():
        assert f"| {claim['id']} |" in report
    # a frictional run of 12 time units has no steady part longer than 500: said, not hidden
    assert "## Left out" in report and "no steady part" in report
    # main's exit status is the comparison's: 1 if a claim failed
    failed = re.search(r"comparison: \d+ pass, \d+ differ from the paper, (\d+) FAIL",
                       text).group(1)
    assert proc.returncode == (1 if int(failed) else 0)
