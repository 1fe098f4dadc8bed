"""The frictional scene's finite-size check (docs/hard_sphere_limit.md, "The width"): per law, k_n
and width (the deck's `width`, disks per row), how the runs ended, each quantity's mean, standard
error and scatter over the selected runs, the width dependence against the widest width, and
which width and how many seeds the wide series takes. The rule was fixed before the check's
runs; its numbers are the constants below."""
import math
from dataclasses import dataclass, field

from .engines import mean_and_error

# The frictional scene's width where params.txt names none (the paper's: 10 disks a row).
PAPER_WIDTH = 10
# the quantities compared across widths
COMPARED = ("E_total", "N_c", "mc_c", "mc_w", "t_multiple")
# |z| above DEPENDS: the quantity depends on the width; above SUGGESTED: a dependence is
# suggested. With eight runs a width the errors are themselves uncertain (Welch's t with ~7
# degrees of freedom exceeds 4 by chance with ~0.5 %: one of 20 comparisons with ~10 %).
DEPENDS_SIGMAS = 4.0
SUGGESTED_SIGMAS = 2.0
# the wide series' candidate widths; the widest is the reference and the default choice
CANDIDATES = (20, 40)
# a candidate must flow: at every k_n at least this fraction of its runs flows to run_time
FLOW_FRACTION = 0.75
# a narrower candidate is taken only if its cost index is smaller by at least this factor
CHEAPER_BY = 1.5
# the quantity whose scatter sets the cost index and the seeds: the paper's
SCATTER_OF = "mc_c"
# selected runs per k_n by the scatter of SCATTER_OF (rule 2's power table: the rows where a
# flat series is called finite in >= 80 % of trials, or its most runs)
RUNS_BY_SCATTER = ((0.10, 4), (0.20, 6), (math.inf, 8))
# the normal quantile of a two-sided 95 % interval (Wilson's interval of a fraction)
Z95 = 1.959964


def width_of(run):
    """The width a run's deck used: params.txt's `width`, which the deck writes for any width but
    the paper's."""
    return int(run.params.get("width", PAPER_WIDTH))


def wilson(successes, n):
    """Wilson's 95 % interval of a fraction successes/n (n > 0)."""
    p = successes / n
    centre = (p + Z95 ** 2 / (2 * n)) / (1 + Z95 ** 2 / n)
    half = Z95 * math.sqrt(p * (1 - p) / n + Z95 ** 2 / (4 * n * n)) / (1 + Z95 ** 2 / n)
    return max(0.0, centre - half), min(1.0, centre + half)


@dataclass
class Cell:
    """The runs of one law, k_n and width: how they ended, and per quantity of COMPARED the
    mean, standard error, scatter (relative standard deviation) over the selected runs."""
    law: str
    kn: float
    width: int
    runs: int = 0
    flowing: int = 0
    stopped: int = 0
    selected: int = 0
    cpu_seconds: float = 0.0
    means: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)
    scatter: dict = field(default_factory=dict)

    @property
    def flow_fraction(self):
        return self.flowing / self.runs

    @property
    def selected_fraction(self):
        return self.selected / self.runs


@dataclass
class Dependence:
    """One quantity at one law and k_n: width W against the reference width."""
    law: str
    kn: float
    quantity: str
    width: int
    reference: int
    z: float
    resolution: float      # DEPENDS_SIGMAS combined errors over the reference mean
    verdict: str           # depends, suggested, none resolved, or undecided (< 2 runs)


def cells_of(runs):
    """{(law, kn, width): Cell} of the frictional runs (those with params: completed)."""
    cells, values = {}, {}
    for run in runs:
        if run.scene != "frictional_flow" or run.params is None:
            continue
        key = (run.params["tangential"], float(run.params["kn"]), width_of(run))
        cell = cells.setdefault(key, Cell(*key))
        cell.runs += 1
        cell.flowing += run.ended == "flowing"
        cell.stopped += run.ended == "stopped"
        cell.cpu_seconds += run.cpu_seconds or 0.0
        if run.observables is not None:
            cell.selected += 1
            for q in COMPARED:
                values.setdefault(key, {}).setdefault(q, []).append(run.observables[q])
    for key, by_quantity in values.items():
        cell = cells[key]
        for q, v in by_quantity.items():
            cell.means[q], cell.errors[q] = mean_and_error(v)
            sd = cell.errors[q] * math.sqrt(len(v))
            cell.scatter[q] = abs(sd / cell.means[q]) if cell.means[q] else math.nan
    return cells


def dependences(cells):
    """Each quantity of COMPARED at each law and k_n, every width against the widest there."""
    out = []
    for law, kn in sorted({(c.law, c.kn) for c in cells.values()}):
        widths = sorted(w for (l, k, w) in cells if (l, k) == (law, kn))
        reference = cells[(law, kn, widths[-1])]
        for width in widths[:-1]:
            cell = cells[(law, kn, width)]
            for q in COMPARED:
                if q not in cell.means or q not in reference.means:
                    continue
                combined = math.hypot(cell.errors[q], reference.errors[q])
                if not combined > 0:
                    out.append(Dependence(law, kn, q, width, reference.width, math.nan,
                                          math.nan, "undecided"))
                    continue
                z = (cell.means[q] - reference.means[q]) / combined
                verdict = ("depends" if abs(z) > DEPENDS_SIGMAS else
                           "suggested" if abs(z) > SUGGESTED_SIGMAS else "none resolved")
                out.append(Dependence(law, kn, q, width, reference.width, z,
                                      DEPENDS_SIGMAS * combined / abs(reference.means[q]),
                                      verdict))
    return out


@dataclass
class Choice:
    law: str
    width: int = None
    why: str = ""
    cost_index: dict = field(default_factory=dict)   # width: C_W
    scatter: float = math.nan                         # of SCATTER_OF at the chosen width
    selected_fraction: float = math.nan
    runs_per_kn: int = None
    seeds: int = None


def geometric_mean(values):
    return math.exp(sum(math.log(v) for v in values) / len(values))


def choose_width(cells, found, law):
    """The rule's choice of the wide series' width and seeds for one law (docs/
    hard_sphere_limit.md): the widest candidate unless a narrower one agrees with it on every
    quantity at every k_n (|z| <= SUGGESTED_SIGMAS) and its cost index is CHEAPER_BY smaller;
    a candidate flows to run_time in at least FLOW_FRACTION of its runs at every k_n."""
    choice = Choice(law)
    # the check's k_n: those where the widest candidate has runs
    kns = sorted({c.kn for c in cells.values() if c.law == law and c.width == max(CANDIDATES)})
    mine = {w: [cells.get((law, kn, w)) for kn in kns] for w in CANDIDATES}
    flowing = [w for w, cs in mine.items()
               if cs and all(c is not None and c.flow_fraction >= FLOW_FRACTION for c in cs)]
    for w, cs in mine.items():
        if all(c is not None and c.selected and SCATTER_OF in c.scatter and
               c.scatter[SCATTER_OF] > 0 for c in cs):
            choice.cost_index[w] = geometric_mean(
                [w * c.scatter[SCATTER_OF] ** 2 / c.selected_fraction for c in cs])
    widest = max(CANDIDATES)
    if widest not in flowing:
        choice.why = (f"width {widest} does not flow to the end in {FLOW_FRACTION:.0%} of its runs "
                      "at every k_n: no width chosen")
        return choice
    choice.width, choice.why = widest, f"width {widest}, the widest"
    for w in sorted(CANDIDATES)[:-1]:
        if w not in flowing or w not in choice.cost_index or widest not in choice.cost_index:
            continue
        agree = [d for d in found if d.law == law and d.width == w and d.reference == widest]
        if agree and all(d.verdict == "none resolved" for d in agree) and \
                choice.cost_index[w] * CHEAPER_BY <= choice.cost_index[widest]:
            choice.width = w
            choice.why = (f"width {w}: it agrees with {widest} on every quantity and its cost "
                          f"index is {choice.cost_index[widest] / choice.cost_index[w]:.2f}x "
                          "smaller")
            break
    else:
        if any(w in choice.cost_index for w in CANDIDATES[:-1]):
            choice.why += " (no narrower candidate both agrees with it and is 1.5x cheaper)"
    cs = [c for c in mine[choice.width] if c.selected]
    if not cs:
        return choice
    pooled = sum(c.selected * c.scatter[SCATTER_OF] ** 2 for c in cs) / sum(c.selected for c in cs)
    choice.scatter = math.sqrt(pooled)
    choice.selected_fraction = sum(c.selected for c in cs) / sum(c.runs for c in cs)
    choice.runs_per_kn = next(r for bound, r in RUNS_BY_SCATTER if choice.scatter <= bound)
    choice.seeds = math.ceil(choice.runs_per_kn / choice.selected_fraction)
    return choice


def analyse_widths(runs):
    """(cells, dependences, choices per law) of runs.load_runs' records."""
    cells = cells_of(runs)
    found = dependences(cells)
    laws = sorted({c.law for c in cells.values() if c.width in CANDIDATES})
    choices = [choose_width(cells, found, law) for law in laws]
    return cells, found, choices
