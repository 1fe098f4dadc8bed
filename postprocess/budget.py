"""The energy budget of a run with energies = yes (energy.txt's e_budget, docs/model.md
section 9): kinetic + gravitational + stored + dissipated energy per flowing disk keeps its
first value up to the integrator's error. A residual beyond that is a budget that does not
close (energy booked twice or not at all, a wall whose work is not counted): the run is
flagged, naming the step and the residual, never passed over in silence.

The bound: velocity Verlet's residual is, exactly, (dt^2/8) (sum |F|^2/m + |T|^2/I at the end -
at the start) (docs/model.md section 9). A contact's force is at most m v omega, omega = pi /
tau_c, on a disk of kinetic energy E = m v^2/2, which puts the term at (pi dt/tau_c)^2 E / 4 =
2.5 (dt/tau_c)^2 E per disk; forces that hold a pile up under gravity add (m g H dt)^2/(8 m) per
disk, below 1e-5 (dt/tau_c)^2 for the piles of these decks. BOUND_FACTOR keeps a factor of four
over the collision's term, and E is counted as at least the energy scale m g d = 1.

The decks apply the same bound as they run (inputs/lib/outputs.lmp's budget_bound,
inputs/lib/budget_check.lmp: a WARNING naming the step), in LAMMPS's variables: one definition
(docs/model.md section 9, this derivation) in two languages, which
tests/lammps/test_budget_warning.py holds to one verdict. A change to the bound is a change to
both."""
import numpy as np

BOUND_FACTOR = 10.0
COLUMN = "e_budget"


def budget_problem(energy, params):
    """Why the run's budget does not close (text naming the first step where its residual is
    beyond BOUND_FACTOR (dt/tau_c)^2 max(1, E) per disk, E the energy per disk then), or None:
    also for a run that printed no budget. energy: energy.txt's columns (io.read_energy)."""
    if COLUMN not in energy:
        return None
    residual = np.abs(energy[COLUMN] - energy[COLUMN][0])
    bound = BOUND_FACTOR * (params["dt"] / params["tau_c"]) ** 2 * np.maximum(
        1.0, energy["e_total"])
    beyond = np.flatnonzero(residual > bound)
    if len(beyond) == 0:
        return None
    k = beyond[0]
    return (f"energy.txt: the energy budget does not close: its residual is {residual[k]:.3g} "
            f"per disk at step {energy['step'][k]:.0f} (t = {energy['time'][k]:g}), beyond the "
            f"integrator's bound {bound[k]:.3g} ({BOUND_FACTOR:g} (dt/tau_c)^2 max(1, E)); its "
            f"largest is {residual.max():.3g}")
