"""Figures of a study (matplotlib, Agg): the paper's panels as PNG files."""
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .durations import density_of_counts  # noqa: E402
from .io import DataError, read_text  # noqa: E402
from .quantities import TABLE  # noqa: E402
from .scenes import scene as scene_of  # noqa: E402
from .selection import Selection, select_steady, window_means  # noqa: E402
from .study import series  # noqa: E402


def save_figure(fig, path, dpi=100):
    """Lays out, writes (making its folder) and closes a figure; the path written."""
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path


def _errorbar(ax, quantity, rows, label, x=None, **style):
    k, v, e = series(rows, quantity)
    style = {"marker": "o", "ms": 4, "capsize": 2, **style}
    ax.errorbar(k if x is None else x(k), v, yerr=np.nan_to_num(e), label=label, **style)


def stiffness(scene, rows, path, variants=()):
    """(a) E against 1/kn, (b) collision rates, (c) contact-time fractions, (d) multiple-contact
    estimates, against kn, with block-average error bars; the variants' points (other labels
    than the main series) as open markers in (a), (b) and (d)."""
    fig, axes = plt.subplots(2, 2, figsize=(10, 8))
    a, b, c, d = axes.flat
    inverse = lambda k: 1.0 / k
    scene_def = scene_of(scene)
    particle = scene_def.particle
    for q in ("E_total", "E_trans", "E_rot"):
        _errorbar(a, q, rows, TABLE[q].short, x=inverse)
    a.set(xscale="log", xlabel="1/k_n", ylabel=f"E per {particle}", title="(a) kinetic energy")
    for q, label in (("N_c", f"N_c ({particle}s)"), ("N_w", "N_w (boundary)")):
        _errorbar(b, q, rows, label)
    kn = np.array([o["kn"] for o in rows])
    if scene_def.rates_log_law:
        b.set(xscale="log", yscale="linear", title="(b) collision rates (N_w ~ ln k_n)")
    else:
        b.set(xscale="log", yscale="log", title="(b) collision rates")
    b.set(xlabel="k_n", ylabel=f"collisions per {particle} per unit time")
    for q in ("t_c", "t_w", "t_multiple"):
        _errorbar(c, q, rows, TABLE[q].short)
    for guide in scene_def.guides if len(kn) > 1 else ():
        values = series(rows, guide.quantity)[1]
        ax = b if guide.panel == "rates" else c
        ax.plot(kn, values[0] * (kn / kn[0]) ** guide.exponent, "k--", lw=1, label=guide.label)
    c.set(xscale="log", yscale="log", xlabel="k_n", ylabel="fraction of time",
          title="(c) contact-time fractions")
    for q in ("mc_c", "mc_w"):
        _errorbar(d, q, rows, TABLE[q].short)
    d.axhline(0, color="gray", lw=0.5)
    d.set(xscale="log", xlabel="k_n", ylabel="fraction of time",
          title="(d) multiple-contact estimates")
    looks = [("s", "dimgray"), ("^", "purple"), ("D", "olive"), ("v", "teal")]
    # the variants' particle contacts, or their boundary contacts where there are no others
    rate, multiple = (("N_c", "mc_c") if any(o["N_c"] > 0 for o in rows) else ("N_w", "mc_w"))
    for (label, points), (marker, color) in zip(variants, looks * len(variants)):
        style = dict(mfc="none", ls=":", color=color, marker=marker)
        _errorbar(a, "E_total", points, f"E ({label})", x=inverse, **style)
        _errorbar(b, rate, points, f"{rate} ({label})", **style)
        _errorbar(d, multiple, points, f"{multiple} ({label})", **style)
    for ax in axes.flat:
        ax.legend(fontsize=6 if variants else 8)
        ax.grid(alpha=0.3, which="both")
    fig.suptitle(f"{scene_def.title}: stiffness dependence")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def profile_figure(scene, rows, path):
    """Density and flow velocity against height of the points `rows` (raw outputs); returns
    the problems: the profiles that could not be read, and why."""
    data, problems = [], []
    for o in rows:
        try:
            data.append((o["kn"], o["outputs"].profile))
        except DataError as error:
            problems.append(str(error))
    if not data:
        raise DataError(f"{scene}: no profile could be read ({'; '.join(problems)})")
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.5), sharey=True)
    for kn, p in data:
        occupied = p["count"] > 0
        a.plot(p["density"], p["y"], label=f"k_n = {kn:g}")
        b.plot(np.where(occupied, p["vx"], np.nan), p["y"], label=f"k_n = {kn:g}")
    a.set(xlabel="number density", ylabel="height y", title="density")
    b.set(xlabel="flow velocity v_x", title="velocity")
    top = max(p["y"][p["count"] > 0].max() for _, p in data if np.any(p["count"] > 0)) + 1
    a.set_ylim(-0.5, top)
    for ax in (a, b):
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    fig.suptitle(f"{scene_of(scene).title}: profiles over the averaging span")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return problems


def vy_figure(rows, trajectories, path):
    """v_y(t) of the single disk at the softest and the stiffest point."""
    fig, ax = plt.subplots(figsize=(9, 3.5))
    for o, style in ((rows[0], "-"), (rows[-1], "--")):
        t, vy = trajectories[o["kn"]]
        start = t[0] + 0.5 * (t[-1] - t[0])
        window = (t >= start) & (t < start + 20)
        ax.plot(t[window] - start, vy[window], style, label=f"k_n = {o['kn']:g}")
    ax.set(xlabel="time (from mid-run)", ylabel="v_y", title="single disk: v_y(t)")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def energy_figure(scene, curves, path, selection=Selection()):
    """E(t) of completed runs, `curves` [(kn, t, E)]. The frictional flow: one panel per k_n
    with every seed's E(t) averaged over windows of `resolution` (the series the selection
    sees), the selected steady parts drawn thick, the accepted energy range shaded."""
    series_by_kn = {}
    for kn, t, e in sorted(curves, key=lambda curve: curve[0]):
        series_by_kn.setdefault(kn, []).append({"time": t, "e_total": e})
    if not scene_of(scene).selects_steady_parts:
        fig, ax = plt.subplots(figsize=(9, 4))
        for kn, runs in series_by_kn.items():
            for energy in runs:
                ax.plot(energy["time"], energy["e_total"], lw=0.8, label=f"k_n = {kn:g}")
        ax.set(xlabel="time", ylabel=f"E per {scene_of(scene).particle}",
               title=f"{scene_of(scene).title}: E(t)")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    else:
        columns = min(3, len(series_by_kn))
        rows = -(-len(series_by_kn) // columns)
        fig, axes = plt.subplots(rows, columns, figsize=(3.6 * columns, 2.2 * rows),
                                 sharex=True, sharey=True, squeeze=False)
        for ax in axes.flat[len(series_by_kn):]:
            ax.set_visible(False)
        for ax, (kn, runs) in zip(axes.flat, series_by_kn.items()):
            ax.axhspan(*selection.energy_range, color="gray", alpha=0.12)
            for energy in runs:
                t, e, _ = window_means(energy["time"], energy["e_total"], selection.resolution)
                line, = ax.plot(t, e, lw=0.4)
                kept, _ = select_steady(t, e, selection.min_length, selection.max_width,
                                        selection.energy_range)
                for a, b in kept:
                    ax.plot(t[a:b], e[a:b], lw=1.6, color=line.get_color())
            ax.set_title(f"k_n = {kn:g} ({len(runs)} runs)", fontsize=9)
            ax.set_ylim(0, 1.5)
            ax.grid(alpha=0.3)
        for ax in axes[-1]:
            ax.set_xlabel("time")
        for ax in axes[:, 0]:
            ax.set_ylabel(f"E per {scene_of(scene).particle} (means over "
                          f"{selection.resolution:g})")
        low, high = selection.energy_range
        fig.suptitle(f"{scene_of(scene).title}: E(t); thick: selected steady parts; grey band: "
                     f"[{low:g}, {high:g}]", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=80 if scene_of(scene).selects_steady_parts else 100)
    plt.close(fig)


def snapshot_figure(scene, point, path):
    """The last frame of a point's snapshots: disks as circles (bumps grey)."""
    snapshots = point / "snapshots.lammpstrj"
    if not snapshots.exists():
        raise DataError(f"{snapshots}: missing")
    text = read_text(snapshots).split("ITEM: TIMESTEP")
    if len(text) < 2:
        raise DataError(f"{point}/snapshots.lammpstrj: no frame")
    lines = text[-1].splitlines()
    try:
        start = next(i for i, l in enumerate(lines) if l.startswith("ITEM: ATOMS"))
        bounds = [float(v) for v in lines[start - 3].split()[:2]]
        atoms = np.loadtxt(lines[start + 1:], ndmin=2)
    except (StopIteration, ValueError, IndexError):
        raise DataError(f"{point}/snapshots.lammpstrj: the last frame is truncated")
    # the height is y in 2D, z in 3D (a side view: spheres as circles of their radius)
    columns = lines[start].split()[2:]
    height = "z" if "z" in columns else "y"
    column_x, column_h = columns.index("x"), columns.index(height)
    fig, ax = plt.subplots(figsize=(10, 3.2))
    for atom in atoms:
        # atom type 2: the bumps (inputs/*.lmp)
        ax.add_patch(plt.Circle((atom[column_x], atom[column_h]), atom[-1],
                                color="0.6" if atom[1] == 2 else "tab:blue", alpha=0.8))
    ax.set_xlim(*bounds)
    ax.set_ylim(-1, max(atoms[:, column_h].max() + 1, 3))
    ax.set_aspect("equal")
    ax.set(xlabel="x (along the slope)", ylabel=height,
           title=f"{scene_of(scene).title}: last snapshot")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


STATE_COLOURS = {"flowing": None, "stopped": "0.8", "accelerating": "mistyrose",
                 "drifting": "lightyellow"}


def _state_regions(ax, rows):
    """Shade each inclination by the state of most of its runs; the counts
    flowing/stopped/accelerating/drifting at the bottom."""
    s = np.array([r["sin_theta"] for r in rows])
    edges = np.r_[s[0] - 0.025, 0.5 * (s[1:] + s[:-1]), s[-1] + 0.025] if len(s) > 1 else \
        np.array([s[0] - 0.025, s[0] + 0.025])
    for r, a, b in zip(rows, edges[:-1], edges[1:]):
        if STATE_COLOURS[r["state"]]:
            ax.axvspan(a, b, color=STATE_COLOURS[r["state"]], lw=0)
        ax.text(r["sin_theta"], 0.02,
                f"{r['flowing']}/{r['stopped']}/{r['accelerating']}/{r['drifting']}",
                transform=ax.get_xaxis_transform(), ha="center", fontsize=6)


def transition_figure(table, path):
    """Per base (columns): (top) the stiffness exponents of N_c and N_w against sin theta,
    with the paper's 0 (collisional) and 0.4 (frictional); (bottom) at the stiffest flowing
    k_n, the multiple-contact fraction (t_c - N_c tau_c)/t_c, the time with two or more
    contacts (boundary contacts included), and the fraction of disk contacts longer than 2 tau_c.
    Inclinations where most runs stopped are grey, where most accelerated pink, where most
    drifted yellow."""
    scenes = sorted({r["scene"] for r in table})
    fig, axes = plt.subplots(2, len(scenes), figsize=(5.5 * len(scenes), 7.5), sharex=True,
                             squeeze=False)
    for column, scene in enumerate(scenes):
        rows = [r for r in table if r["scene"] == scene]
        s = np.array([r["sin_theta"] for r in rows])
        top, bottom = axes[:, column]

        def plot(ax, key, label, marker):
            values = np.array([r.get(key, np.nan) for r in rows], dtype=float)
            errors = np.array([r.get(key + "_err", np.nan) for r in rows], dtype=float)
            ax.errorbar(s, values, yerr=np.nan_to_num(errors), marker=marker, ms=5, capsize=2,
                        label=label)
        plot(top, "exponent_N_c", "N_c exponent", "o")
        plot(top, "exponent_N_w", "N_w exponent", "s")
        top.axhline(0.0, color="k", lw=0.6, ls=":", label="collisional (paper): 0")
        top.axhline(0.4, color="k", lw=0.6, ls="--", label="frictional (paper): 0.4")
        top.set(ylabel="stiffness exponent", title=f"{scene_of(scene).base}")
        plot(bottom, "mc_fraction", f"({TABLE['mc_c'].short})/t_c", "o")
        plot(bottom, "t_multiple", "time with >= 2 contacts (any kind)", "^")
        bottom.plot(s, [r.get("tail_disk", np.nan) for r in rows], "D--",
                    label="disk contacts > 2 tau_c")
        bottom.axhline(0.0, color="k", lw=0.6, ls=":")
        bottom.set(xlabel="sin theta", ylabel="fraction (stiffest flowing k_n)")
        for ax in (top, bottom):
            _state_regions(ax, rows)
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7)
    fig.suptitle("collisional-frictional transition; grey: most runs stopped, pink: most "
                 "accelerated, yellow: most drifted; counts flowing/stopped/accelerating/"
                 "drifting", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def duration_figure(densities, edges, path):
    """P(tau/tau_c) of disk contacts and P(tau/tau_w) of boundary contacts (columns) per base
    (rows), one line per inclination, log-log; densities: {(scene, sin_theta, kn): {kind:
    density}}."""
    scenes = sorted({key[0] for key in densities})
    fig, axes = plt.subplots(len(scenes), 2, figsize=(10, 4 * len(scenes)), squeeze=False)
    centres = np.sqrt(edges[1:] * edges[:-1])
    for row, scene in enumerate(scenes):
        for column, (kind, unit) in enumerate((("disk", "tau_c"), ("boundary", "tau_w"))):
            ax = axes[row, column]
            for (s, sin_theta, kn), density in sorted(densities.items()):
                if s == scene and np.any(density[kind] > 0):
                    shown = np.where(density[kind] > 0, density[kind], np.nan)
                    ax.plot(centres, shown, "-", marker=".", lw=1,
                            label=f"sin theta {sin_theta:g} (k_n {kn:g})")
            ax.axvline(1.0, color="k", lw=0.6, ls=":")
            ax.set(xscale="log", yscale="log", xlabel=f"tau / {unit}",
                   ylabel=f"P(tau / {unit})",
                   title=f"{scene_of(scene).base}: {kind} contacts")
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=7)
    fig.suptitle("contact durations at the stiffest flowing k_n (a binary contact lasts 1)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def duration_stiffness(scene, series, edges, path):
    """P(tau/tau_c) of particle contacts and P(tau/tau_w) of boundary contacts (columns) of each
    series of a scene (rows), one line per k_n, log-log; series: [(label, [(kn, pooled)])]
    with durations.pooled's result per k_n."""
    particle = scene_of(scene).particle
    fig, axes = plt.subplots(len(series), 2, figsize=(10, 3.8 * len(series)), squeeze=False)
    centres = np.sqrt(edges[1:] * edges[:-1])
    for row, (label, points) in enumerate(series):
        colours = plt.cm.viridis(np.linspace(0, 0.9, len(points)))
        for column, (kind, unit, name) in enumerate((
                ("disk", "tau_c", f"{particle}-{particle}"), ("boundary", "tau_w", "boundary"))):
            ax = axes[row, column]
            for (kn, pooled), colour in zip(points, colours):
                counts, total = pooled[kind]["histogram"], pooled[kind]["contacts"]
                density = density_of_counts(counts, total, edges)
                if np.any(density > 0):
                    ax.plot(centres, np.where(density > 0, density, np.nan), "-", marker=".",
                            lw=1, color=colour, label=f"k_n {kn:g} ({total} contacts)")
            ax.axvline(1.0, color="k", lw=0.6, ls=":")
            ax.set(xscale="log", yscale="log", xlabel=f"tau / {unit}",
                   ylabel=f"P(tau / {unit})")
            ax.set_title(textwrap.fill(f"{label or 'main series'}: {name} contacts", 60),
                         fontsize=8)
            ax.grid(alpha=0.3, which="both")
            ax.legend(fontsize=6)
    fig.suptitle(f"{scene_of(scene).title}: contact durations (a binary contact lasts 1)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def limit_figure(decisions, path):
    """The hard-sphere-limit rule's data and fits (docs/hard_sphere_limit.md): per quantity, the
    per-k_n means with their errors, the pure power law and the power law onto a floor, the
    floor's bootstrap interval; and the running exponents."""
    fig, axes = plt.subplots(1, len(decisions) + 1, figsize=(4.2 * (len(decisions) + 1), 4))
    for ax, d in zip(axes, decisions):
        s = d.series
        ax.errorbar(s.kn, s.value, yerr=s.error, fmt="o", ms=4, capsize=2, label="runs' mean")
        if d.fits is not None:
            k = np.geomspace(s.kn[0], s.kn[-1], 100)
            ax.plot(k, d.fits.power_amplitude * (k / s.kn[0]) ** -d.fits.b_power, "--",
                    label=f"k_n^-{d.fits.b_power:.2f}")
            ax.plot(k, d.fits.floor + d.fits.floor_amplitude * (k / s.kn[0]) ** -d.fits.b_floor,
                    "-", label=f"floor {d.fits.floor:.3g}")
            low, high = d.floor_interval
            ax.axhspan(low, high, color="0.85", zorder=0, label="floor 95 % (bootstrap)")
        ax.set(xscale="log", yscale="log", xlabel="k_n", title=f"{TABLE[d.quantity].title}: {d.verdict}")
        ax.legend(fontsize=7)
        running = [r for r in d.running if np.isfinite(r[2])]
        if running:
            centre = [np.sqrt(a * b) for a, b, *_ in running]
            axes[-1].errorbar(centre, [r[2] for r in running], yerr=[r[3] for r in running],
                              fmt="o-", ms=4, capsize=2, label=TABLE[d.quantity].title)
    axes[-1].axhline(0.0, color="k", lw=0.5)
    axes[-1].set(xscale="log", xlabel="k_n", ylabel="d ln m / d ln k_n",
                 title="running exponents")
    axes[-1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def dissipation_figure(groups, path):
    """Where the energy goes as k_n grows (postprocess/dissipation.py): per scene and law, the
    shares of the dissipated energy lost in lasting contacts, in multiple contacts and in
    binary collisions, and the negative sliding work's, with their errors over the runs."""
    from .dissipation import per_kn
    fig, axes = plt.subplots(1, len(groups), figsize=(4.2 * len(groups), 3.8), squeeze=False)
    for ax, group in zip(axes[0], groups):
        rows = per_kn(group)
        kn = [r[0] for r in rows]
        for share, label in (("lasting", "lasting (> 3 binary durations)"),
                             ("multiple", "in a multiple contact"), ("binary", "binary"),
                             ("negative_sliding", "negative sliding work")):
            ax.errorbar(kn, [r[2][share][0] for r in rows],
                        yerr=[np.nan_to_num(r[2][share][1]) for r in rows], fmt="o-", ms=4,
                        capsize=2, label=label)
        ax.axhline(0.0, color="k", lw=0.5)
        verdict = group.decision.verdict if group.decision else "n/a"
        ax.set(xscale="log", xlabel="k_n", ylabel="share of the dissipated energy",
               title=textwrap.fill(f"{group.scene} ({group.law}): lasting share {verdict}", 40))
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
