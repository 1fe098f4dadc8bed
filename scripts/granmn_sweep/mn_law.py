"""The contact law's derived numbers (docs/model.md section 3) as the plugin's own header
computes them, through its command-line face build/plugin/mn-law: the one place that runs it."""
import subprocess
from pathlib import Path


class LawError(ValueError):
    """mn-law refused the material (its message says why)."""


def derived(tool, kn, e, beta, shape="disc"):
    """{name: value} printed by `tool --shape SHAPE KN E BETA`: q, eta_n, kt, eta_t, tau_c,
    tau_w, e_w and the integrators' stability limits; shape disc (the 2D styles) or sphere (the
    3D styles, docs/model.md 3.1)."""
    tool = Path(tool)
    if not tool.exists():
        raise LawError(f"{tool} is missing: run ./scripts/build.sh first")
    out = subprocess.run([str(tool), "--shape", shape, repr(kn), repr(e), repr(beta)],
                         capture_output=True, text=True)
    if out.returncode != 0:
        raise LawError(f"kn {kn} e {e} beta {beta}: {out.stderr.strip()}")
    return {name: float(value) for name, value in (line.split() for line in out.stdout.splitlines())}
