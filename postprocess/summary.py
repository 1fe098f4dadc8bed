"""Compact summaries of a sweep's runs (docs/sweeps.md, "Summaries"): one JSON file per run,
<scene>/<point>.json, holding its RunRecord (postprocess/record.py) but the observables, which
are recomputed on reading with the reader's selection. A few kB where the raw outputs take
MB: committed under data/, they let the report and compare be redone without rerunning.

The file: an object with `schema` (SCHEMA), `version` (VERSION), `steady_rule` (the
min_length and max_width the steady parts were found with), then the record's fields
(point, scene, ended, stopped_at, failure, variables, params, measured, energy, cpu_seconds,
reason); measured's steady parts are keyed by resolution written with %g; a run with contact
rows adds measured.contacts (durations.run_contacts: the histogram of P(tau) on
durations.DURATION_EDGES, the split of the time with two or more contacts and, where the run
booked its contacts' energies, where they went: durations.dissipation_split) and
measured.contacts_problem, which readers of older summaries do without. A file that is not
this, or of another version, is refused by name (the run is left out, saying why)."""
import json
import math
from pathlib import Path

from .durations import DISSIPATION_NAMES, DURATION_EDGES, LASTING, LASTING_ALSO, SPLIT_NAMES
from .io import CONTACT_KINDS, DataError, checked_agreement, checked_name, checked_params, \
    checked_values, checked_variables, unique_keys
from .observables import RESOLUTIONS
from .quantities import BLOCKS, SIGNED
from .record import DRAWN_WINDOW, ENDINGS, RunRecord, run_name
from .rundir import SUMMARY_SUFFIX
from .scenes import scene
from .selection import Selection

SCHEMA = "granmn-run-summary"
# Version 1: measured holds the steady parts at RESOLUTIONS found with the default
# Selection's min_length and max_width.
VERSION = 1
FIELDS = ("point", "scene", "ended", "stopped_at", "failure", "variables", "params",
          "measured", "energy", "cpu_seconds", "reason")


def summary_text(record, selection):
    """The summary of a raw RunRecord whose steady parts were found with `selection`: JSON, one
    field per line."""
    data = {"schema": SCHEMA, "version": VERSION,
            "steady_rule": {"min_length": selection.min_length,
                            "max_width": selection.max_width}}
    for name in FIELDS:
        data[name] = getattr(record, name)
    data["point"] = run_name(record)
    if data["measured"] is not None:
        measured = dict(data["measured"])
        measured["steady"] = {f"{r:g}": parts for r, parts in measured["steady"].items()}
        for name in ("period", "bump_time"):     # nan (no period found) is not JSON
            if name in measured and measured[name] is not None and math.isnan(measured[name]):
                measured[name] = None
        data["measured"] = measured
    return "{\n" + ",\n".join(f"{json.dumps(k)}: {json.dumps(v, sort_keys=True, allow_nan=False)}"
                              for k, v in data.items()) + "\n}\n"


def energy_end(record):
    """The time to which a record's E(t) reaches (0: it has none)."""
    e = record.energy
    return e["t0"] + e["window"] * len(e["E"]) if e else 0.0


def lost(old, new):
    """What the RunRecord `new` lacks that `old`, of the same run, has, in words: None if
    `new` is as complete. Less complete: a run that did not complete where the old one did;
    outputs that could not be read, or a measurement with a problem, where the old ones could
    be; an E(t) that ends earlier (a shorter span); no contact rows where the old had them."""
    completed = ("flowing", "stopped")
    if old.ended in completed and new.ended not in completed:
        return f"it holds a run that completed ({old.ended}); the new one's {new.reason}"
    if old.reason is None and new.reason is not None:
        return f"its outputs were read; the new one's: {new.reason}"
    if old.measured and not old.measured["problem"] and new.measured and \
            new.measured["problem"]:
        return f"it was measured; the new one's: {new.measured['problem']}"
    if energy_end(new) < energy_end(old):
        return (f"its E(t) reaches t = {energy_end(old):g}, the new one's only "
                f"{energy_end(new):g}")
    if old.measured and old.measured.get("contacts") and not (
            new.measured and new.measured.get("contacts")):
        return "it holds the durations of the contact rows; the new one not"
    return None


def read_summaries(directory, selection=Selection()):
    """The RunRecords of a directory of summaries (<scene>/<point>.json), sorted by path; a
    summary that cannot be read is a record ended 'unreadable' with the reason."""
    directory = Path(directory)
    paths = sorted(directory.glob("*/*.json"))
    if not paths:
        raise DataError(f"{directory}: no sweep points here (no <scene>/<point>/point.json) "
                        "and no summaries (<scene>/<point>.json)")
    if selection.resolution not in RESOLUTIONS:
        raise DataError(f"{directory}: summaries hold the steady parts at resolutions "
                        f"{', '.join(f'{r:g}' for r in RESOLUTIONS)} only: resolution "
                        f"{selection.resolution:g} needs the raw outputs")
    records = []
    for path in paths:
        try:
            records.append(read_summary(path, selection))
        except DataError as error:
            records.append(RunRecord(point=path, scene=path.parent.name, source="summary",
                                     ended="unreadable", reason=str(error)))
    return records


class _Checker:
    """Reads a summary's values, each checked for its kind; a DataError names the file and
    the value."""

    def __init__(self, path):
        self.path = path

    def fail(self, where, what):
        raise DataError(f"{self.path}: corrupt summary: {where} {what}")

    def numeric(self, value, where):
        """value as a float if it is a JSON number (a double can hold), else the failure."""
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(where, f"is {value!r}, not a finite number")
        try:
            return float(value)
        except OverflowError:
            self.fail(where, f"is {value!r}, not a finite number")

    def number(self, value, where, optional=False, non_negative=False):
        """A value of the run, which io.checked_values takes: the rule the raw reader applies
        to energy.txt's values."""
        if value is None and optional:
            return None
        return float(checked_values(self.numeric(value, where),
                                    lambda: f"{self.path}: corrupt summary: {where}", non_negative))

    def text(self, value, where, optional=False):
        if value is None and optional:
            return None
        if not isinstance(value, str):
            self.fail(where, f"is {value!r}, not text")
        return value

    def mapping(self, value, where, optional=False):
        if value is None and optional:
            return None
        if not isinstance(value, dict):
            self.fail(where, "is not an object")
        return value

    def numbers(self, value, where, non_negative=False):
        if not isinstance(value, list):
            self.fail(where, "is not a list")
        values = [self.numeric(v, f"{where}[{k}]") for k, v in enumerate(value)]
        return checked_values(values, lambda k: f"{self.path}: corrupt summary: {where}[{k}]",
                              non_negative).tolist()

    def key(self, data, name, where):
        if name not in data:
            self.fail(where, f"has no {name}")
        return data[name]

    def part(self, data, where, names, blocks):
        """A steady part or the window: the numbers `names`, and the blocks if `blocks`."""
        data = self.mapping(data, where)
        part = {n: self.number(self.key(data, n, where), f"{where}.{n}") for n in names}
        if "span" in part and not part["span"] > 0:
            # the weight of the run among its seeds
            self.fail(f"{where}.span", f"is {part['span']:g}, not a time span > 0")
        if blocks:
            columns = self.mapping(self.key(data, "blocks", where), f"{where}.blocks")
            part["blocks"] = {q: self.numbers(self.key(columns, q, f"{where}.blocks"),
                                              f"{where}.blocks.{q}",
                                              non_negative=q not in SIGNED)
                              for q in BLOCKS}
            if len({len(v) for v in part["blocks"].values()}) > 1:
                self.fail(f"{where}.blocks", "has columns of different lengths")
        return part

    def measured(self, data):
        data = self.mapping(data, "measured")
        problem = self.text(self.key(data, "problem", "measured"), "measured.problem",
                            optional=True)
        steady = self.mapping(self.key(data, "steady", "measured"), "measured.steady")
        measured = {"problem": problem, "steady": {}}
        for key, parts in steady.items():
            try:
                resolution = float(key)
            except ValueError:
                resolution = None
            if resolution not in RESOLUTIONS:
                self.fail(f"measured.steady.{key}", "is not a resolution this version keeps")
            if not isinstance(parts, list):
                self.fail(f"measured.steady.{key}", "is not a list")
            names = ("start", "stop", "mean") + (("span", "mean_samples") if problem is None
                                                 else ())
            measured["steady"][resolution] = [
                self.part(p, f"measured.steady.{key}[{k}]", names, blocks=problem is None)
                for k, p in enumerate(parts)]
        if problem is not None:
            return measured
        measured["window"] = self.part(self.key(data, "window", "measured"), "measured.window",
                                       ("start", "stop", "span"), blocks=True)
        n_boundary = self.number(self.key(data, "n_boundary", "measured"),
                                 "measured.n_boundary")
        if n_boundary < 0 or n_boundary != int(n_boundary):
            self.fail("measured.n_boundary", f"is {n_boundary:g}, not a count")
        measured["n_boundary"] = int(n_boundary)
        measured["rest_at"] = self.number(self.key(data, "rest_at", "measured"),
                                          "measured.rest_at", optional=True)
        if "period_problem" in data:
            measured["period_problem"] = self.text(data["period_problem"],
                                                   "measured.period_problem", optional=True)
            for name in ("period", "bump_time"):
                value = self.number(self.key(data, name, "measured"), f"measured.{name}",
                                    optional=True)
                measured[name] = math.nan if value is None else value
        if "budget_problem" in data:
            measured["budget_problem"] = self.text(data["budget_problem"],
                                                   "measured.budget_problem")
        if "contacts" in data:
            measured["contacts"] = self.contacts(data["contacts"])
            measured["contacts_problem"] = self.text(data.get("contacts_problem"),
                                                     "measured.contacts_problem", optional=True)
        return measured

    def contacts(self, data):
        """measured.contacts (durations.run_contacts), or None."""
        if data is None:
            return None
        data = self.mapping(data, "measured.contacts")
        out = {"histogram": {}, "contacts": {}, "tail": {}}
        histogram = self.mapping(self.key(data, "histogram", "measured.contacts"),
                                 "measured.contacts.histogram")
        contacts = self.mapping(self.key(data, "contacts", "measured.contacts"),
                                "measured.contacts.contacts")
        tail = self.mapping(self.key(data, "tail", "measured.contacts"), "measured.contacts.tail")
        for kind in CONTACT_KINDS:
            where = f"measured.contacts.histogram.{kind}"
            counts = self.numbers(self.key(histogram, kind, "measured.contacts.histogram"), where)
            if len(counts) != len(DURATION_EDGES) - 1 or any(c < 0 or c != int(c) for c in counts):
                self.fail(where, f"is not {len(DURATION_EDGES) - 1} counts")
            total = self.number(self.key(contacts, kind, "measured.contacts.contacts"),
                                f"measured.contacts.contacts.{kind}")
            if total < sum(counts) or total != int(total):
                self.fail(f"measured.contacts.contacts.{kind}",
                          f"is {total:g}, not a count of at least the histogram's {sum(counts):g}")
            longer = self.number(self.key(tail, kind, "measured.contacts.tail"),
                                 f"measured.contacts.tail.{kind}")
            if not 0 <= longer <= total or longer != int(longer):
                self.fail(f"measured.contacts.tail.{kind}", f"is {longer:g}, not a count of at "
                          f"most {total:g}")
            out["histogram"][kind], out["contacts"][kind] = [int(c) for c in counts], int(total)
            out["tail"][kind] = int(longer)
        if "split" in data:
            split = self.mapping(data["split"], "measured.contacts.split")
            keys = sorted(f"{t:g}" for t in (LASTING, LASTING_ALSO))
            if sorted(split) != keys:
                self.fail("measured.contacts.split", f"has the thresholds {sorted(split)}, not "
                          f"{keys}")
            out["split"] = {}
            for key in keys:
                where = f"measured.contacts.split.{key}"
                part = self.mapping(split[key], where)
                out["split"][key] = {name: self.number(self.key(part, name, where),
                                                       f"{where}.{name}", optional=True)
                                     for name in SPLIT_NAMES}
        if "dissipation" in data:
            where = "measured.contacts.dissipation"
            part = self.mapping(data["dissipation"], where)
            out["dissipation"] = {name: self.number(self.key(part, name, where),
                                                    f"{where}.{name}", optional=True)
                                  for name in DISSIPATION_NAMES}
            for name in ("negative_sliding_contacts", "contacts"):
                count = out["dissipation"][name]
                if count is None or count < 0 or count != int(count):
                    self.fail(f"{where}.{name}", f"is {count}, not a count")
                out["dissipation"][name] = int(count)
        return out

    def energy(self, data):
        data = self.mapping(data, "energy")
        window = self.number(self.key(data, "window", "energy"), "energy.window")
        if window < DRAWN_WINDOW:
            self.fail("energy.window", f"is {window:g}, below {DRAWN_WINDOW:g}")
        return {"window": window, "t0": self.number(self.key(data, "t0", "energy"), "energy.t0"),
                "E": self.numbers(self.key(data, "E", "energy"), "energy.E",
                                  non_negative=True)}


def read_summary(path, selection=Selection()):
    """The RunRecord of one summary file, every value checked; a DataError names the file and
    what is wrong with it. Its steady parts must have been found with the selection's
    min_length and max_width (selection None: with any)."""
    path = Path(path)
    try:
        data = json.loads(path.read_text(), object_pairs_hook=unique_keys(path))
    except (ValueError, UnicodeDecodeError) as error:
        raise DataError(f"{path}: not a run summary: not valid JSON ({error})")
    if not isinstance(data, dict) or data.get("schema") != SCHEMA:
        raise DataError(f"{path}: not a run summary (no \"schema\": \"{SCHEMA}\")")
    if data.get("version") != VERSION:
        raise DataError(f"{path}: run summary version {data.get('version')!r}; this code reads "
                        f"version {VERSION} (python3 -m postprocess summarize writes it)")
    check = _Checker(path)
    for name in FIELDS + ("steady_rule",):
        check.key(data, name, "the summary")
    rule = check.mapping(data["steady_rule"], "steady_rule")
    found = {n: check.number(check.key(rule, n, "steady_rule"), f"steady_rule.{n}")
             for n in ("min_length", "max_width")}
    wanted = found if selection is None else {"min_length": selection.min_length,
                                              "max_width": selection.max_width}
    if found != wanted:
        raise DataError(f"{path}: its steady parts were found with {rule}, not with the "
                        f"selection's {wanted}: the raw outputs are needed")
    ended = check.text(data["ended"], "ended")
    if ended not in ENDINGS[:4]:
        check.fail("ended", f"is {ended!r}, not one of {', '.join(ENDINGS[:4])}")
    if ended in ("failed", "incomplete"):
        # such a run has no outputs to take values from (runs.read_run)
        for name in ("stopped_at", "params", "measured", "energy"):
            if data[name] is not None:
                check.fail(name, f"is there, but the run {ended}: it has no values")
        if data["reason"] is None:
            check.fail("reason", f"is null, but the run {ended}")
    if ended == "flowing" and data["stopped_at"] is not None:
        check.fail("stopped_at", "is there, but the run ended flowing (its pile did not stop)")
    record = RunRecord(point=path, scene=check.text(data["scene"], "scene"), source="summary",
                       ended=ended,
                       stopped_at=check.number(data["stopped_at"], "stopped_at", optional=True),
                       failure=check.text(data["failure"], "failure", optional=True),
                       variables=check.mapping(data["variables"], "variables", optional=True),
                       cpu_seconds=check.number(data["cpu_seconds"], "cpu_seconds",
                                                optional=True),
                       reason=check.text(data["reason"], "reason", optional=True))
    name = f"{path.parent.name}/{path.name.removesuffix(SUMMARY_SUFFIX)}"
    if check.text(data["point"], "point") != name:
        check.fail("point", f"is {data['point']!r}, but the file is {name}{SUMMARY_SUFFIX}")
    if record.scene != path.parent.name:
        check.fail("scene", f"is {record.scene!r}, but the file is in {path.parent.name}/")
    try:
        scene(record.scene)
    except KeyError as error:
        check.fail("the summary", f"names an {error.args[0]}")
    if record.variables is not None:
        checked_name(checked_variables(record.variables, f"{path}: corrupt summary: variables"),
                     name, f"{path}: corrupt summary: variables", "its file")
    params = check.mapping(data["params"], "params", optional=True)
    if params is not None:
        # numbers as params.txt gives them (floats: a JSON integer is one too)
        record.params = checked_params(
            {name: value if isinstance(value, str) else check.number(value, f"params.{name}")
             for name, value in params.items()}, f"{path}: params")
        if record.variables is not None:
            checked_agreement(record.variables, record.params,
                              f"{path}: corrupt summary: variables", "params")
    if data["measured"] is not None:
        if record.params is None:
            check.fail("measured", "is there without params")
        if record.variables is None:
            check.fail("measured", "is there without variables")
        record.measured = check.measured(data["measured"])
    if data["energy"] is not None:
        record.energy = check.energy(data["energy"])
    if record.reason is None and record.measured is None:
        check.fail("the summary", "has neither measured nor a reason")
    return record
