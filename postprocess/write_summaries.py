"""The summarize command: one compact summary (postprocess/summary.py says the format) per run
of a results directory."""
import sys
from pathlib import Path

from . import rundir
from .io import DataError
from .observables import RESOLUTIONS
from .record import run_name
from .runs import read_run
from .selection import Selection
from .summary import lost, read_summary, summary_text


def write_summaries(results_dir, to, selection=Selection(), replace=False):
    """Summarises every point of a results directory into `to`/<scene>/<point>.json, the
    frictional steady parts found with the selection's min_length and max_width (which the
    summary records: a reader must ask for the same). A summary there that is more complete
    than the new one (lost), or that this code cannot read, is kept unless `replace`. Returns
    the paths written and [(path kept, why)]."""
    results_dir = Path(results_dir)
    if not results_dir.is_dir():
        raise DataError(f"{results_dir}: no such results directory")
    points = sorted(p for p in results_dir.glob("*/*") if (p / rundir.POINT).exists())
    if not points:
        raise DataError(f"{results_dir}: no sweep points here (no <scene>/<point>/point.json)")
    written, kept = [], []
    for point in points:
        record = read_run(point, RESOLUTIONS, selection)
        path = Path(to) / f"{run_name(record)}{rundir.SUMMARY_SUFFIX}"
        if path.exists() and not replace:
            try:
                why = lost(read_summary(path, selection=None), record)
            except DataError as error:
                why = f"this code cannot read it ({error})"
            if why:
                kept.append((path, why))
                continue
        if record.measured and record.measured.get("budget_problem"):
            print(f"warning: {point}: {record.measured['budget_problem']}", file=sys.stderr)
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(summary_text(record, selection))
        written.append(path)
    return written, kept
