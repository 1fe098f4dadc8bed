"""The contact law's derived numbers (docs/model.md section 3) as the plugin's own header
computes them, through its command-line face build/plugin/mn-law: the one place that runs it."""
import subprocess
from pathlib import Path


class LawError(ValueError):
    """mn-law refused the material (its message says why)."""


def derived(tool, kn, e, beta):
    """{name: value} printed by `tool KN E BETA`: eta_n, kt, eta_t, tau_c, tau_w, e_w and the
    integrators' stability limits."""
    tool = Path(tool)
    if not tool.exists():
        raise LawError(f"{tool} is missing: run ./scripts/build.sh first")
    out = subprocess.run([str(tool), repr(kn), repr(e), repr(beta)], capture_output=True,
                         text=True)
    if out.returncode != 0:
        raise LawError(f"kn {kn} e {e} beta {beta}: {out.stderr.strip()}")
    return {name: float(value) for name, value in (line.split() for line in out.stdout.splitlines())}
