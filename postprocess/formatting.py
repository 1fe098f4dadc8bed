"""Numbers, verdict tallies and the contact-split table as the writers print them."""
import numpy as np

from .durations import LASTING, LASTING_ALSO, TAIL_CUT
from .reference import tally


def fmt(value, error=None):
    if value is None or not np.isfinite(value):
        return "n/a"
    text = f"{value:.4g}"
    if error is not None and np.isfinite(error):
        text += f" ± {error:.2g}"
    return text


def comparison_line(results):
    """The one-line tally of a comparison."""
    counts = tally(results)
    nothing = counts["not evaluated"] == len(results)
    return (f"comparison: {counts['pass']} pass, {counts['differs']} differ from the paper, "
            f"{counts['FAIL']} FAIL, {counts['not evaluated']} not evaluated"
            f"{': nothing could be evaluated' if nothing else ''}")


def split_lines(splits):
    """Markdown: per k_n the mean over runs of the split and, from two runs on, its standard
    error over the runs (splits: [(kn, {threshold: split})], thresholds durations.LASTING and
    LASTING_ALSO; a value a run lacks (None) is left out)."""
    a, b = LASTING, LASTING_ALSO
    lines = [f"| k_n | runs | >= 2 contacts (counters) | from rows | lasting (> {a:g} tau) | "
             f"bursts (<= {a:g} tau) | lasting (> {b:g} tau) | bursts (<= {b:g} tau) | "
             f"unseen (> window) | contact time in > {a:g} tau contacts |", "|---|" + "---|" * 9]
    for k in sorted({kn for kn, _ in splits}):
        mine = [s for kn, s in splits if kn == k]

        def mean(threshold, name, digits=4):
            values = [s[threshold][name] for s in mine if s[threshold][name] is not None]
            if not values:
                return "nan"
            text = f"{np.mean(values):.{digits}f}"
            if len(values) > 1:
                text += f" +- {np.std(values, ddof=1) / np.sqrt(len(values)):.{digits}f}"
            return text
        lines.append(f"| {k:.4g} | {len(mine)} | {mean(a, 't_multiple_counters')} | "
                     f"{mean(a, 't_multiple_rows')} | {mean(a, 'lasting')} | "
                     f"{mean(a, 'bursts')} | {mean(b, 'lasting')} | "
                     f"{mean(b, 'bursts')} | {mean(a, 'unseen')} | "
                     f"{mean(a, 'lasting_share_of_contact_time', 3)} |")
    return lines + [""]


def tail_lines(runs_contacts, particle):
    """Markdown: per k_n the weight of P(tau)'s tail, the fraction of a run's contacts lasting
    longer than TAIL_CUT binary durations (tau_c; tau_w against the boundary), as the mean over
    the runs with rows and, from two runs on, its standard error over them (runs_contacts:
    [(kn, durations.run_contacts result)]; a run without contacts of a kind is left out of that
    kind's mean)."""
    lines = [f"| k_n | runs | {particle}-{particle} contacts | > {TAIL_CUT:g} tau_c | "
             f"boundary contacts | > {TAIL_CUT:g} tau_w |", "|---|---|---|---|---|---|"]
    for k in sorted({kn for kn, _ in runs_contacts}):
        mine = [c for kn, c in runs_contacts if kn == k]
        cells = []
        for kind in ("disk", "boundary"):
            weights = [c["tail"][kind] / c["contacts"][kind] for c in mine if c["contacts"][kind]]
            text = f"{np.mean(weights):.4f}" if weights else "nan"
            if len(weights) > 1:
                text += f" +- {np.std(weights, ddof=1) / np.sqrt(len(weights)):.4f}"
            cells += [str(sum(c["contacts"][kind] for c in mine)), text]
        lines.append(f"| {k:.4g} | {len(mine)} | " + " | ".join(cells) + " |")
    return lines + [""]
