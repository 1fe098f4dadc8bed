"""The accuracy study (scripts/studies/accuracy.py) runs from one command and writes its table and figure (shortened)."""
import re
import subprocess
import sys

from granmn_run import BUILD_PATHS, ROOT

# the build under test (build-2026/ for LAMMPS 2026), not build/
BUILD = BUILD_PATHS.directory


def test_accuracy_study_writes_its_tables_and_figure(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "scripts.studies.accuracy", "--quick",
                           "--output", str(tmp_path), "--build", str(BUILD)],
                          cwd=ROOT, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    report = (tmp_path / "accuracy.md").read_text()
    for section in ("## Binary collision and bouncing ball", "## single_disk", "## collisional_flow",
                    "## Cheapest choice per observable", "## Cost against stiffness"):
        assert section in report
    assert (tmp_path / "accuracy.png").stat().st_size > 10000
    # the restitution converges: its error at tau_c/200 is below that at tau_c/50, both schemes
    errors = {(i, f): float(err) for i, f, err in
              re.findall(r"\| (verlet|ab2) \| 1/(\d+) \| \S+ \| ([+-]\S+) \|", report)}
    for integrator in ("verlet", "ab2"):
        assert abs(errors[integrator, "200"]) < abs(errors[integrator, "50"])
    exponent = float(re.search(r"cost ~ kn\^(\S+)", report).group(1))
    assert 0 < exponent < 1
