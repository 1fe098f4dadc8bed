"""The observables of a run, one table (docs/model.md section 6): each quantity's name, how the
report, the terminal and the figures call it, its unit and the point files it is computed from
(postprocess/rundir.py). Every module takes its names and labels from here; the selections at
the end are the few subsets the analyses and the reports use, named once.

Units are those of the scenes (docs/model.md section 1): length sigma (the largest disk's
diameter), mass m (its mass), time t0 = sqrt(sigma/g). The energies, rates and fractions are
per disk (the boundary's per disk of the bottom layer in the frictional flow)."""
from dataclasses import dataclass

from . import rundir


@dataclass(frozen=True)
class Quantity:
    """name: the key of a run's observables (and <name>_err its error); label: what the reports'
    text and the terminal call it; short: a table's column header, a curve in a figure's
    legend; title: a figure panel's title (narrow); unit; files: the point's files it comes
    from; signed: whether it can be negative."""
    name: str
    label: str
    unit: str
    files: tuple
    signed: bool = False
    short: str = None
    title: str = None

    def __post_init__(self):
        for short in ("short", "title"):
            if getattr(self, short) is None:
                object.__setattr__(self, short, self.label)


_ENERGY = (rundir.ENERGY, rundir.PARAMS)     # a column of energy.txt per disk (n_mobile)
# the boundary's rates are per disk of the bottom layer: those counts.txt says touched it
_BOUNDARY = (rundir.ENERGY, rundir.PARAMS, rundir.COUNTS)

# in the order of the per-block tables (observables.span_blocks)
TABLE = {q.name: q for q in (
    Quantity("E_trans", "E_trans", "m g sigma", _ENERGY, short="translational"),
    Quantity("E_rot", "E_rot", "m g sigma", _ENERGY, short="rotational"),
    Quantity("E_total", "E", "m g sigma", _ENERGY),
    Quantity("N_c", "N_c", "1/t0", _ENERGY),
    Quantity("N_w", "N_w", "1/t0", _BOUNDARY),
    Quantity("t_c", "t_c", "1", _ENERGY),
    Quantity("t_w", "t_w", "1", _BOUNDARY),
    Quantity("t_multiple", "time with two or more contacts", "1", _ENERGY,
             short="two or more contacts", title="time with >= 2 contacts"),
    # t - N tau is negative where contacts last less than tau on average
    Quantity("mc_c", "t_c - N_c tau_c", "1", _ENERGY, signed=True),
    Quantity("mc_w", "t_w - N_w tau_w", "1", _BOUNDARY, signed=True),
    Quantity("z", "z", "1", _ENERGY),
)}

# what every block of a run's averaging span holds (observables, summaries)
BLOCKS = tuple(TABLE)
# the can-be-negative ones (a summary's other block values must be >= 0)
SIGNED = tuple(q for q in TABLE if TABLE[q].signed)
# the columns of the per-scene and per-run tables (observables_<scene>.csv, runs.csv)
COLUMNS = ("E_trans", "E_rot", "E_total", "N_c", "N_w", "t_c", "t_w", "mc_c", "mc_w",
           "t_multiple", "z")
# the per-scene table of the report
SCENE_TABLE = ("E_total", "N_c", "N_w", "t_c", "t_w", "mc_c", "mc_w", "t_multiple")
# those a variant of a series is compared on with the main series, in the report
VARIANTS = ("E_total", "N_c", "N_w", "t_c", "t_w", "mc_c", "mc_w")
# those whose running exponents in k_n the report lists, the energy last
EXPONENTS = ("N_c", "N_w", "t_c", "t_w", "mc_c", "mc_w", "t_multiple", "z", "E_total")
