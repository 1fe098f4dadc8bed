"""The study report: tables, fits, figures, the comparison with the references, left-out points."""
import csv
import datetime
from pathlib import Path

import numpy as np

from . import figures
from .io import DataError, read_trajectory
from .reference import evaluate
from .study import QUANTITIES, fit_log, fit_power, series


def fmt(value, error=None):
    if value is None or not np.isfinite(value):
        return "n/a"
    text = f"{value:.4g}"
    if error is not None and np.isfinite(error):
        text += f" ± {error:.2g}"
    return text


def fits(scene, rows):
    """The fits the paper's figures invite, as (what, value, error) lines."""
    out = []
    if len(rows) < 2:
        return out
    if scene == "frictional_flow":
        for q in ("N_c", "N_w"):
            a, e = fit_power(*series(rows, q)[:2])
            out.append((f"{q} ~ k_n^a (paper guide a = 0.4)", a, e))
    if scene == "single_disk":
        a, e = fit_log(*series(rows, "N_w")[:2])
        out.append(("N_w against ln k_n: slope", a, e))
    if scene == "collisional_flow":
        a, e = fit_power(*series(rows, "t_c")[:2])
        out.append(("t_c ~ k_n^a (expected -1/2)", a, e))
        a, e = fit_power(*series(rows, "t_w")[:2])
        out.append(("t_w ~ k_n^a (paper: slightly slower than -1/2)", a, e))
    return out


def write_tables(scenes, out):
    for scene, rows in scenes.items():
        with open(out / f"observables_{scene}.csv", "w", newline="") as f:
            writer = csv.writer(f)
            header = ["kn", "tau_c", "tau_w", "span", "n_boundary"]
            for q in QUANTITIES:
                header += [q, q + "_err"]
            writer.writerow(header + ["point"])
            for o in rows:
                writer.writerow([o[k] for k in header] + [o["point"]])


def make_figures(scenes, completed, out):
    """{scene: [(caption, file name)]}, and problems met. Time series and snapshots of every
    completed point; the stiffness dependences and profiles of the usable ones."""
    made, problems = {}, []
    for scene, points in completed.items():
        items = made.setdefault(scene, [])
        rows = scenes.get(scene, [])
        jobs = [("kinetic energy against time", f"energy_{scene}.png",
                 lambda p, s=scene, c=points: figures.energy_figure(s, c, p)),
                ("snapshot (stiffest point)", f"snapshot_{scene}.png",
                 lambda p, s=scene, c=points: figures.snapshot_figure(s, c[-1], p))]
        if rows:
            jobs += [("stiffness dependence", f"stiffness_{scene}.png",
                      lambda p, s=scene, r=rows: figures.stiffness(s, r, p)),
                     ("profiles", f"profiles_{scene}.png",
                      lambda p, s=scene, r=rows: figures.profile_figure(s, r, p))]
        if scene == "single_disk" and rows:
            def vy(p, r=rows):
                trajectories = {}
                for o in (r[0], r[-1]):
                    t = read_trajectory(o["point"])
                    trajectories[o["kn"]] = (t["time"], t["vy"])
                figures.vy_figure(r, trajectories, p)
            jobs.append(("v_y(t) at the softest and the stiffest point", "vy_single_disk.png", vy))
        for caption, name, job in jobs:
            try:
                job(out / name)
                items.append((caption, name))
            except DataError as error:
                problems.append(f"{name}: {error}")
    return made, problems


def write_report(sweep_dir, scenes, left_out, completed, out):
    out.mkdir(parents=True, exist_ok=True)
    write_tables(scenes, out)
    made, problems = make_figures(scenes, completed, out)
    results = evaluate(scenes)
    with open(out / "comparison.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["id", "scene", "quantity", "measure", "measured", "low", "high",
                         "status", "source", "why"])
        for claim, value, status in results:
            writer.writerow([claim["id"], claim["scene"], claim["quantity"], claim["measure"],
                             value, claim["low"], claim["high"], status, claim["source"],
                             claim["why"]])

    lines = [f"# Stiffness study: {sweep_dir}", "",
             f"Written {datetime.datetime.now():%Y-%m-%d %H:%M} by `python3 -m postprocess "
             f"report`. Errors are standard errors of block averages within each run "
             f"(5 blocks per averaging span).", ""]
    for scene in completed:
        rows = scenes.get(scene, [])
        lines += [f"## {figures.TITLES[scene]}", ""]
        if not rows:
            lines += ["No usable point (see Left out).", ""]
        lines += [
                  "| k_n | E | N_c | N_w | t_c | t_w | t_c - N_c tau_c | t_w - N_w tau_w | "
                  "two or more contacts | span | point |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"] if rows else []
        for o in rows:
            lines.append("| " + " | ".join(
                [f"{o['kn']:g}"] + [fmt(o[q], o[q + "_err"]) for q in
                                    ("E_total", "N_c", "N_w", "t_c", "t_w", "mc_c", "mc_w",
                                     "t_multiple")] + [f"{o['span']:g}", o["label"]]) + " |")
        notes = [f"k_n = {o['kn']:g}: {o['notes']}" for o in rows if o["notes"]]
        if scene == "frictional_flow" and rows:
            notes.append("N_w and t_w are per disk of the bottom layer (disks that touched the "
                         "floor in the averaging window; the paper: during the averaging span).")
        if scene == "single_disk" and rows:
            notes.append("v_y periods: " + ", ".join(f"{o['kn']:g}: {fmt(o['period'])}"
                                                      for o in rows))
        lines += [""] + [f"- {n}" for n in notes] + [""]
        scene_fits = fits(scene, rows)
        if scene_fits:
            lines += ["Fits:", ""] + [f"- {what}: {fmt(v, e)}" for what, v, e in scene_fits] + [""]
        for caption, name in made.get(scene, []):
            lines += [f"![{caption}]({name})", ""]
    lines += ["## Comparison with the references", "",
              "| claim | quantity | measured | accepted range | status | source |",
              "|---|---|---|---|---|---|"]
    for claim, value, status in results:
        lines.append(f"| {claim['id']} | {claim['quantity']} ({claim['measure']}) | "
                     f"{fmt(value)} | [{claim['low']:g}, {claim['high']:g}] | {status} | "
                     f"{claim['source']} |")
    lines += ["", "The table is also in `comparison.csv`, with the reason for each tolerance.", ""]
    if left_out or problems:
        lines += ["## Left out", ""]
        lines += [f"- `{point}`: {reason}" for point, reason in left_out]
        lines += [f"- figure {p}" for p in problems]
        lines.append("")
    (out / "report.md").write_text("\n".join(lines))
    return out / "report.md", results
