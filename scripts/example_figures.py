"""The figure of an example's comparison script (drum_repose.py, funnel_discharge.py,
pour_packing.py): one axes, the runs as labelled lines, saved as a PNG."""


def axes(size=(6, 3.5)):
    """A figure of one axes, drawn without a display."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt.subplots(figsize=size)


def save(fig, ax, path):
    """Legend, grid and layout, then the file; says where it went."""
    import matplotlib.pyplot as plt
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print(f"figure: {path}")
