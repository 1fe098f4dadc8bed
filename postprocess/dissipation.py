"""Where the contacts' energy goes as k_n grows (docs/hard_sphere_limit.md, "Where the energy
goes: the rule"): per run, the shares of the dissipated energy lost in lasting contacts, in
multiple contacts and in binary collisions (durations.dissipation_split, kept in a run's
measured contacts); per series (a scene and its tangential law), their means over the runs at
each k_n and rule 2 of postprocess/limit.py on the lasting share."""
from dataclasses import dataclass, field

import numpy as np

from . import limit
from .durations import DISSIPATION_NAMES, ROWS_MARGIN
from .rundir import point_name

# the shares a series reports per k_n (the lasting share is the one the rule judges)
SHARES = ("lasting", "multiple", "binary", "sliding", "negative_sliding")
JUDGED = "lasting"


@dataclass
class Group:
    """The runs of one scene and tangential law: per k_n the runs' shares; the verdict."""
    scene: str
    law: str
    runs: list = field(default_factory=list)     # dicts: kn, span, the shares, counts
    left_out: list = field(default_factory=list)  # (point, why)
    decision: limit.Decision = None


def law_of(record):
    """The run's tangential law (params.txt's; "none" for a frictionless scene)."""
    return str((record.params or {}).get("tangential") or "none")


def run_values(record):
    """{kn, span, the shares, counts} of one record, or the reason it has none."""
    if record.ended != "flowing":
        return f"it ended {record.ended}" + (f" at t = {record.stopped_at:g}"
                                             if record.stopped_at is not None else "")
    contacts = (record.measured or {}).get("contacts")
    if not contacts or "dissipation" not in contacts:
        return "no contact energies (run with energies = yes, rows = yes)"
    values = contacts["dissipation"]
    if values["lasting"] is None:
        return "its contacts dissipated nothing in the rows window"
    rows_time = float(record.variables.get("rows_time", 0))
    return {"point": point_name(record.variables), "kn": float(record.params["kn"]),
            "span": rows_time - ROWS_MARGIN,
            "budget_problem": (record.measured or {}).get("budget_problem") or "",
            "cpu_seconds": record.cpu_seconds,
            **{name: values[name] for name in DISSIPATION_NAMES}}


def analyse_dissipation(records, samples=limit.BOOTSTRAP):
    """[Group] of the records (runs.load_runs), sorted by scene and law; a record that is not
    of a scene with energies (no contacts.txt at all) is left out of every group."""
    groups = {}
    for record in records:
        key = (record.scene, law_of(record))
        group = groups.setdefault(key, Group(*key))
        values = run_values(record)
        if isinstance(values, str):
            group.left_out.append((record.point, values))
        else:
            group.runs.append(values)
    out = []
    for key in sorted(groups):
        group = groups[key]
        if not group.runs:
            continue
        group.decision = limit.decide(group.runs, JUDGED, samples=samples, rule=2)
        out.append(group)
    return out


def per_kn(group):
    """[(kn, runs, {share: (mean, error)}, negative sliding contacts per 1000 contacts, rows'
    D over the global dissipation)] of a group, each mean weighted by the runs' spans."""
    out = []
    for kn in sorted({r["kn"] for r in group.runs}):
        members = [r for r in group.runs if r["kn"] == kn]
        spans = [r["span"] for r in members]
        means = {}
        for share in SHARES:
            values = [r[share] for r in members]
            means[share] = (limit.weighted_mean(values, spans) if len(values) > 1
                            else (float(values[0]), np.nan))
        contacts = sum(r["contacts"] for r in members)
        negative = 1000.0 * sum(r["negative_sliding_contacts"] for r in members) / contacts \
            if contacts else np.nan
        ratio = [r["dissipated"] / r["global_dissipated"] for r in members
                 if r["global_dissipated"]]
        out.append((kn, len(members), means, negative,
                     float(np.mean(ratio)) if ratio else np.nan))
    return out
