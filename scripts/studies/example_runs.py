"""What the example comparison scripts (drum_repose.py, funnel_discharge.py, pour_packing.py)
share: a LAMMPS log's thermo rows by the columns of their own header, and their figure (one
axes, the runs as labelled lines, saved as a PNG)."""
from pathlib import Path

import numpy as np


def thermo(path, needed):
    """{column: array} of every thermo row of a log.lammps whose header (the line that starts
    with `Step`) names all of `needed`, the runs one after the other; a step that ends one run
    and starts the next is kept once (its first row). Stops with a message naming the file if
    there is none."""
    rows, header = {}, None
    for line in Path(path).read_text().splitlines():
        words = line.split()
        if words[:1] == ["Step"]:
            header = words if all(n in words for n in needed) else None
            continue
        if header is None or len(words) != len(header):
            if words[:2] == ["Loop", "time"]:
                header = None
            continue
        try:
            values = [float(w) for w in words]
        except ValueError:
            continue
        rows.setdefault(values[0], dict(zip(header, values)))
    if not rows:
        raise SystemExit(f"{path}: no thermo rows with the columns {', '.join(needed)}")
    ordered = [rows[step] for step in sorted(rows)]
    return {name: np.array([r[name] for r in ordered]) for name in ordered[0]}


def axes(size=(6, 3.5)):
    """A figure of one axes, drawn without a display."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt.subplots(figsize=size)


def save(fig, ax, path):
    """Legend, grid and layout, then the file; says where it went."""
    from postprocess.figures import save_figure
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, which="both")
    print(f"figure: {save_figure(fig, path)}")


def curves_figure(path, curves, xlabel, ylabel, title, log_y=False):
    """One curve per {label: (x, y)}, in one axes, saved to path."""
    fig, ax = axes((6, 3.5))
    for label, (x, y) in curves.items():
        (ax.semilogy if log_y else ax.plot)(x, y, lw=1.2, label=label)
    ax.set(xlabel=xlabel, ylabel=ylabel, title=title)
    save(fig, ax, path)
