"""What a run's contact rows (contacts.txt, `-var rows yes`) say: the distribution of contact
durations P(tau) and what the time with two or more contacts is made of. The one place that
reads durations from rows: measure() keeps a run's histogram and split in its measured
values (so that summaries carry them), the report, the limit rule and the transition study
take them from there or from here."""
import numpy as np

from . import rundir
from .io import CONTACT_KINDS, DataError

# P(tau): log bins of tau/tau_c (tau/tau_w for boundary contacts), ten per decade; the tail
# beyond TAIL_CUT binary durations holds the lasting contacts (a binary collision lasts 1).
DURATION_EDGES = np.logspace(-1, 4, 51)
TAIL_CUT = 2.0
# a contact lasting more than this many binary durations is a lasting one (the split); the
# split is also given for LASTING_ALSO
LASTING, LASTING_ALSO = 3.0, 10.0
# a split is made over rows windows (rows_time, time units) longer than this: run_split and
# run_dissipation leave out ROWS_MARGIN at the window's end
SPLIT_MIN_ROWS_TIME = 1.0
ROWS_MARGIN = 0.5


def contact_durations(rows, tau_c, tau_w, since):
    """{'disk': tau/tau_c, 'boundary': tau/tau_w} of the contacts that ended at or after
    `since`. Contacts counted by when they end have the steady state's distribution of
    durations: no long contact is cut off at the start or the end of the stretch."""
    ended = rows["start"] + rows["duration"] >= since
    unit = {"disk": tau_c, "boundary": tau_w}
    return {kind: rows["duration"][ended & (rows["kind"] == code)] / unit[kind]
            for kind, code in CONTACT_KINDS.items()}


def duration_density(scaled, edges=DURATION_EDGES):
    """P(tau/tau_c) on the bins `edges`: counts / (all contacts x bin width), so that it
    integrates to the fraction of contacts inside the bins."""
    scaled = np.asarray(scaled, dtype=float)
    counts, _ = np.histogram(scaled, edges)
    if len(scaled) == 0:
        return np.full(len(edges) - 1, np.nan)
    return counts / (len(scaled) * np.diff(edges))


def density_of_counts(counts, total, edges=DURATION_EDGES):
    """duration_density from a histogram already made (counts in the bins of `edges`, `total`
    contacts in all, some perhaps outside the bins)."""
    counts = np.asarray(counts, dtype=float)
    if total <= 0:
        return np.full(len(edges) - 1, np.nan)
    return counts / (total * np.diff(edges))


def tail_fraction(scaled, cut=TAIL_CUT):
    """The fraction of contacts lasting longer than `cut` binary durations."""
    scaled = np.asarray(scaled, dtype=float)
    return float(np.mean(scaled > cut)) if len(scaled) else np.nan


def multiple_contact_split(rows, tau_c, tau_w, start, stop, n_particles, lasting=LASTING):
    """From contact rows (io.read_rows: id_i, id_j, kind, start, duration): per
    particle and unit time over [start, stop], the time with two or more contacts, split into
    the part during which at least one of the contacts is a lasting one (longer than `lasting`
    times tau_c, or tau_w against the boundary) and the part made only of short ones (bursts of
    overlapping collisions); and the share of all contact time in lasting contacts.
    Rows are those of the contacts that ended within the rows window: choose [start, stop] so
    that no contact overlapping it can end after the window (stop <= window end - the longest
    duration of interest)."""
    if not stop > start:
        raise ValueError(f"an empty window [{start:g}, {stop:g}]")
    with_disk = rows["kind"] == CONTACT_KINDS["disk"]
    begin = rows["start"]
    end = begin + rows["duration"]
    unit = np.where(with_disk, tau_c, tau_w)
    long = rows["duration"] > lasting * unit
    # each contact belongs to particle i, and a particle-particle contact to j as well
    owner = np.concatenate([rows["id_i"], rows["id_j"][with_disk]]).astype(int)
    b = np.concatenate([begin, begin[with_disk]])
    e = np.concatenate([end, end[with_disk]])
    is_long = np.concatenate([long, long[with_disk]])
    b, e = np.clip(b, start, stop), np.clip(e, start, stop)
    keep = e > b
    owner, b, e, is_long = owner[keep], b[keep], e[keep], is_long[keep]
    multiple = lasting_part = 0.0
    for particle in np.unique(owner):
        mine = owner == particle
        times = np.concatenate([b[mine], e[mine]])
        step = np.concatenate([np.ones(mine.sum()), -np.ones(mine.sum())])
        long_step = np.concatenate([is_long[mine], -1.0 * is_long[mine]])
        order = np.lexsort((step, times))    # at equal times an end before a start
        times, count, long_count = times[order], np.cumsum(step[order]), \
            np.cumsum(long_step[order])
        spans = np.diff(times)
        several = count[:-1] >= 2
        multiple += spans[several].sum()
        lasting_part += spans[several & (long_count[:-1] >= 1)].sum()
    length = n_particles * (stop - start)
    durations = np.clip(end, start, stop) - np.clip(begin, start, stop)
    total = durations.sum() + durations[with_disk].sum()
    return {"t_multiple_rows": multiple / length, "lasting": lasting_part / length,
            "bursts": (multiple - lasting_part) / length,
            "lasting_share_of_contact_time":
                (durations[long].sum() + durations[long & with_disk].sum()) / total
                if total > 0 else np.nan}


# what run_split gives (the split's names in a summary)
SPLIT_NAMES = ("t_multiple_rows", "lasting", "bursts", "lasting_share_of_contact_time",
               "t_multiple_counters", "unseen")


def run_split(point, rows_time, first, lasting=LASTING, margin=ROWS_MARGIN):
    """multiple_contact_split over the rows window of a run (an io.Point), [average_start,
    average_start + rows_time - margin] (a contact overlapping it that ends after the rows
    window lasts longer than `margin`: such contacts have no row and their part, `unseen`, is
    the counters' time with two or more contacts over the window minus the rows': lasting by
    construction). first: energy.txt's first row after the counters' restart at average_start
    (observables.averaging_rows; a row written at the restart's very step holds the sums from
    before it), where the counters' part of the window starts."""
    params, energy = point.params, point.energy
    start = params["average_start"]
    stop = start + rows_time - margin
    if not stop > start + margin:
        raise ValueError(f"{point.directory}: no rows window longer than {2 * margin:g} "
                         "(rows_time)")
    split = multiple_contact_split(point.rows, params["tau_c"], params["tau_w"], start, stop,
                                   params["n_mobile"], lasting)
    t = energy["time"]
    a, b = first, np.argmin(np.abs(t - stop))
    if not b > a:
        raise ValueError(f"{point.directory}: energy.txt has no rows in the rows window")
    counted = (energy["time_multiple"][b] - energy["time_multiple"][a]) / (
        params["n_mobile"] * (t[b] - t[a]))
    split["t_multiple_counters"] = counted
    split["unseen"] = max(counted - split["t_multiple_rows"], 0.0)
    return split


def multiple_contacts(rows):
    """Per row, whether the contact overlapped in time another contact (of any row) of one of
    its particles: one of its disks had two contacts or more while it lasted. Touching in time
    (one ends at the step the other begins) is not overlapping."""
    with_disk = rows["kind"] == CONTACT_KINDS["disk"]
    index = np.arange(len(rows["kind"]))
    owner = np.concatenate([rows["id_i"], rows["id_j"][with_disk]]).astype(int)
    index = np.concatenate([index, index[with_disk]])
    begin = rows["start"][index]
    end = begin + rows["duration"][index]
    order = np.lexsort((begin, owner))
    owner, index, begin, end = owner[order], index[order], begin[order], end[order]
    found = np.zeros(len(rows["kind"]), dtype=bool)
    for first, last in zip(*group_bounds(owner)):
        b, e = begin[first:last], end[first:last]
        # sorted by start: a contact overlaps an earlier one if any earlier one ends after it
        # begins, a later one if the next one begins before it ends
        earlier = np.concatenate([[-np.inf], np.maximum.accumulate(e)[:-1]]) > b
        later = np.concatenate([b[1:] < e[:-1], [False]])
        found[index[first:last][earlier | later]] = True
    return found


def group_bounds(sorted_keys):
    """The [first, last) bounds of each run of equal values in a sorted array."""
    if len(sorted_keys) == 0:
        return np.array([], dtype=int), np.array([], dtype=int)
    starts = np.flatnonzero(np.concatenate([[True], sorted_keys[1:] != sorted_keys[:-1]]))
    return starts, np.concatenate([starts[1:], [len(sorted_keys)]])


# what dissipation_split gives (its names in a summary)
DISSIPATION_NAMES = ("dissipated", "lasting", "multiple", "binary", "sliding",
                     "negative_sliding", "negative_sliding_contacts", "contacts",
                     "global_dissipated")


def dissipation_split(rows, tau_c, tau_w, start, stop, lasting=LASTING):
    """Where the contacts that ended within [start, stop] lost their energy (rows of a run with
    energies = yes: io.read_rows with the dissipated columns), docs/hard_sphere_limit.md "Where
    the energy goes": `dissipated`, what they dissipated in all (D), and as shares of D what was
    lost in lasting contacts (longer than `lasting` binary durations), in contacts that
    overlapped another contact of one of their particles (multiple_contacts; a contact counted
    whole), in the rest (binary: short and alone), and while sliding; `negative_sliding`, the
    sum of the sliding work of the contacts whose sliding work is negative (the literal u_t's
    sliding that gives energy back) as a share of D, and `negative_sliding_contacts` how many
    of the `contacts` there were. Shares are None where D is not positive."""
    if not stop > start:
        raise ValueError(f"an empty window [{start:g}, {stop:g}]")
    end = rows["start"] + rows["duration"]
    ended = (end >= start) & (end <= stop)
    unit = np.where(rows["kind"] == CONTACT_KINDS["disk"], tau_c, tau_w)
    long = rows["duration"] > lasting * unit
    several = multiple_contacts(rows)
    dissipated = rows["dissipated"]
    sliding = rows["dissipated_sliding"]
    total = float(dissipated[ended].sum())
    negative = ended & (sliding < 0)

    def share(mask):
        return float(dissipated[ended & mask].sum()) / total if total > 0 else None
    return {"dissipated": total, "lasting": share(long), "multiple": share(several),
            "binary": share(~long & ~several),
            "sliding": float(sliding[ended].sum()) / total if total > 0 else None,
            "negative_sliding": float(sliding[negative].sum()) / total if total > 0 else None,
            "negative_sliding_contacts": int(np.count_nonzero(negative)),
            "contacts": int(np.count_nonzero(ended))}


# energy.txt's columns of the energy the contacts dissipated since the run began (a run with
# energies = yes)
DISSIPATED_COLUMNS = ("dissipated_normal", "dissipated_sticking", "dissipated_sliding")


def run_dissipation(point, rows_time, margin=ROWS_MARGIN):
    """dissipation_split over the rows window of a run (an io.Point with energy columns in its
    rows), as run_split's window, with `global_dissipated`: the growth of the whole system's
    dissipated energy (energy.txt) over the same window, which the rows' D differs from by
    what the contacts open at the window's edges lost outside it."""
    params = point.params
    start = params["average_start"]
    stop = start + rows_time - margin
    split = dissipation_split(point.rows, params["tau_c"], params["tau_w"], start, stop)
    energy = point.energy
    missing = [c for c in DISSIPATED_COLUMNS if c not in energy]
    if missing:
        raise DataError(f"{point.directory / rundir.ENERGY}: the header names no column "
                        f"{', '.join(missing)}, which a run whose rows have energies prints")
    a, b = (int(np.argmin(np.abs(energy["time"] - t))) for t in (start, stop))
    split["global_dissipated"] = float(sum(energy[c][b] - energy[c][a]
                                           for c in DISSIPATED_COLUMNS))
    return split


def run_contacts(point, first):
    """What measure() keeps of a run's rows (None if it has none): the histogram of the
    durations of the contacts that ended after average_start, per kind, on DURATION_EDGES
    ({"histogram": {kind: counts}, "contacts": {kind: all contacts, inside the bins or not},
    "tail": {kind: those longer than TAIL_CUT binary durations}}),
    and, where the rows cover a window (rows_time > SPLIT_MIN_ROWS_TIME), the split of the
    time with two or more contacts ({"split": {"3": ..., "10": ...}}, keyed by the lasting
    threshold written with %g). first: as for run_split."""
    if not (point.directory / "contacts.txt").exists():
        return None
    params = point.params
    scaled = contact_durations(point.rows, params["tau_c"], params["tau_w"],
                               params["average_start"])
    out = {"histogram": {k: [int(c) for c in np.histogram(v, DURATION_EDGES)[0]]
                         for k, v in scaled.items()},
           "contacts": {k: int(len(v)) for k, v in scaled.items()},
           "tail": {k: int(np.count_nonzero(v > TAIL_CUT)) for k, v in scaled.items()}}
    try:
        rows_time = float(point.variables.get("rows_time", 0) or 0)
    except DataError:
        rows_time = 0.0     # not a sweep's point: no rows window known
    if rows_time > SPLIT_MIN_ROWS_TIME:
        out["split"] = {f"{lasting:g}": {k: float(v) if np.isfinite(v) else None for k, v in
                                         run_split(point, rows_time, first, lasting).items()}
                        for lasting in (LASTING, LASTING_ALSO)}
        if "dissipated" in point.rows:
            out["dissipation"] = run_dissipation(point, rows_time)
    return out


def pooled(runs_contacts):
    """The histograms, contact and tail counts of several runs (run_contacts' results, None
    left out) added up, with "runs" (how many) and "splits" ([{lasting: split}] with the
    thresholds as numbers) of those that have a split; None if no run has rows."""
    present = [c for c in runs_contacts if c is not None]
    if not present:
        return None
    out = {kind: {"histogram": np.sum([c["histogram"][kind] for c in present], axis=0),
                  "contacts": sum(c["contacts"][kind] for c in present),
                  "tail": sum(c["tail"][kind] for c in present)} for kind in CONTACT_KINDS}
    out["runs"] = len(present)
    out["splits"] = [{float(k): v for k, v in c["split"].items()} for c in present
                     if "split" in c]
    return out
