"""Run lmp with the gran/mn plugin on a deck and read back what it printed.

The paths come from ctest's environment (GRANMN_LMP, GRANMN_PLUGIN, GRANMN_MPIEXEC), and
GRANMN_MPI whether that lmp has MPI."""
import functools
import os
import re
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest

from postprocess.io import read_energy, read_params
from scripts.granmn_sweep.build_layout import build_layout
from scripts.granmn_sweep.mn_law import derived

LMP = os.environ.get("GRANMN_LMP", "lmp")
PLUGIN = os.environ.get("GRANMN_PLUGIN", "granmnplugin.so")
MPIEXEC = os.environ.get("GRANMN_MPIEXEC", "mpirun")
# OFF: a serial LAMMPS (scripts/build.sh --serial): a test that runs more than one rank, or
# mpirun, is skipped with this reason
SERIAL = os.environ.get("GRANMN_MPI", "ON").upper() in ("OFF", "NO", "FALSE", "0")
# the build the plugin is in (build/plugin/granmnplugin.so): its mn-law, engine, LIGGGHTS
BUILD_PATHS = build_layout(Path(PLUGIN).resolve().parents[1])
SERIAL_REASON = "a serial LAMMPS (GRANMN_MPI=OFF, LAMMPS's STUBS MPI) runs on one rank, no mpirun"
needs_mpi = pytest.mark.skipif(SERIAL, reason=SERIAL_REASON)

# A 2D disk box with LAMMPS's granular essentials; decks add atoms, styles and runs.
HEADER = """
plugin load {plugin}
units lj
dimension 2
atom_style sphere
atom_modify map array
boundary p p p
comm_modify vel yes
neighbor 0.1 bin
"""


@dataclass
class Run:
    returncode: int
    output: str
    workdir: Path
    results: dict = field(default_factory=dict)

    def result(self, name):
        """Numbers of the line `RESULT name v1 v2 ...` printed by the deck."""
        if name not in self.results:
            raise AssertionError(f"deck printed no RESULT {name}; output tail:\n{self.output[-3000:]}")
        return self.results[name]

    def table(self, filename):
        return np.loadtxt(self.workdir / filename, ndmin=2)

    def atoms(self, filename="final.txt"):
        """A LAMMPS text dump (one snapshot, sorted by id) as {column: array}."""
        lines = (self.workdir / filename).read_text().splitlines()
        start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
        names = lines[start].split()[2:]
        data = np.loadtxt(lines[start + 1:], ndmin=2)
        return {name: data[:, k] for k, name in enumerate(names)}


ROOT = Path(__file__).resolve().parents[2]
INPUTS = ROOT / "inputs"


def _run(cmd, workdir, check):
    proc = subprocess.run(cmd, cwd=workdir, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=1200)
    run = Run(proc.returncode, proc.stdout, Path(workdir))
    for line in proc.stdout.splitlines():
        m = re.match(r"^RESULT (\S+)(.*)$", line)
        if m:
            run.results[m.group(1)] = [float(x) for x in m.group(2).split()]
    if check and proc.returncode != 0:
        raise AssertionError(f"lmp failed ({proc.returncode}):\n{proc.stdout[-4000:]}")
    return run


@functools.lru_cache(maxsize=None)
def installed_packages():
    """The LAMMPS packages this lmp was built with (its -h listing)."""
    listing = subprocess.run([LMP, "-h"], capture_output=True, text=True, timeout=60).stdout
    match = re.search(r"^Installed packages:\s*\n\s*\n(.*?)\n\s*\n", listing, re.M | re.S)
    return set(match.group(1).split()) if match else set()


def _command(nprocs):
    if nprocs > 1 and SERIAL:
        pytest.skip(f"{nprocs} ranks: {SERIAL_REASON}")
    return ([MPIEXEC, "-np", str(nprocs)] if nprocs > 1 else []) + [LMP]


def run_scene(scene, workdir, nprocs=1, check=True, **variables):
    """Runs inputs/<scene>.lmp with its outputs in workdir and the given deck variables."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    settings = dict(plugin=PLUGIN, lib=INPUTS / "lib", out=workdir, **variables)
    cmd = _command(nprocs) + ["-in", str(INPUTS / f"{scene}.lmp"), "-log",
                              str(workdir / "log.lammps"), "-nocite"]
    for name, value in settings.items():
        cmd += ["-var", name, str(value)]
    return _run(cmd, workdir, check)


def run_lammps(deck, workdir, nprocs=1, header=True, check=True):
    """Runs `deck` (the HEADER first unless header=False) in workdir with nprocs MPI ranks."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    text = (HEADER.format(plugin=PLUGIN) if header else "") + deck
    (workdir / "in.deck").write_text(text)
    cmd = _command(nprocs) + ["-in", "in.deck", "-log", "log.lammps", "-nocite"]
    return _run(cmd, workdir, check)


def energy_of(directory):
    """A run directory's energy.txt as the post-processing reads it: {column: array} by its
    header, with the time column (step * dt of its params.txt)."""
    return read_energy(directory, read_params(directory))


def law(kn, e, beta, shape="disc"):
    """The coefficients of docs/model.md section 3 as the header derives them (build/plugin/mn-law,
    next to the plugin) for discs or (shape "sphere") solid spheres: one copy of the mapping,
    checked against its definitions by the unit tests."""
    return derived(BUILD_PATHS.mn_law, kn, e, beta, shape)


def restitution_error_bound(e, dt_over_tau):
    """How far velocity Verlet may put a measured restitution from the analytic one.

    The damping force switches on and off up to one step away from the true contact start and
    end (each at most 2 eta v dt of relative velocity, eta the mode's damping rate), and it sees
    velocities half a step old (eta dt (1+e) v0 over the contact). With eta tau = |ln e| for the
    mode, |e_measured - e| <= 3 (1 + e) |ln e| dt/tau, plus the second-order error of the
    smooth part, (dt/tau)^2."""
    return 3 * (1 + e) * abs(np.log(e)) * dt_over_tau + dt_over_tau ** 2


def ab2_error_bound(dt_over_tau):
    """How far fix nve/ab2 may put a measured restitution (or duration/tau) of a contact that
    begins half-way through a step (the collision decks' phase) from the analytic one.

    Adams-Bashforth 2 for velocities with the trapezoidal rule for positions and u_t is second
    order: over half an oscillation of angular frequency w = pi/tau its error is c (w dt)^2,
    c of the order of AB2's error constant 5/12 (measured: 0.2). A contact starting half-way
    through a step costs nothing at first order (docs/choosing_dt.md). Bound: (pi dt/tau)^2."""
    return (np.pi * dt_over_tau) ** 2


# Order of convergence: halving dt divides the error, or the difference of the measurements at
# dt and dt/2, by 2^order. Velocity Verlet's damping sees velocities half a step old: its
# restitutions are first order (ratio 2); fix nve/ab2 is second order (ratio 4). A first-order
# part (ratio 2), such as u_t advanced by v_t(t) dt under AB2, fails the lower bound 3, which
# any second-order quantity (velocity Verlet's energy budget too) must pass.
SECOND_ORDER_RATIO = 3.0
ORDER_RATIO = {"verlet": (1.5, 2.6), "ab2": (SECOND_ORDER_RATIO, np.inf)}


def convergence_ratio(values):
    """(m(dt) - m(dt/2)) / (m(dt/2) - m(dt/4)) for measurements at dt, dt/2, dt/4: 2^order,
    whatever the exact value (which the geometry of an oblique impact shifts a little)."""
    return (values[0] - values[1]) / (values[1] - values[2])
