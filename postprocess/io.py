"""Reading a point's output files (docs/scenes.md). Every problem raises DataError naming the
file and what is wrong: nothing broken is averaged silently."""
import json
from functools import cached_property
from pathlib import Path

import numpy as np

from . import rundir


class DataError(Exception):
    """A point's output is missing, truncated or inconsistent."""


def output_schema(path=Path(__file__).with_name("output_schema.txt")):
    """The styles' output schema (plugin/mn_output_schema.h, through `mn-law --columns`): its
    tables by name, each the words of its line."""
    return {words[0]: tuple(words[1:]) for words in
            (line.split() for line in path.read_text(encoding="utf-8").splitlines())
            if words and not words[0].startswith("#")}


SCHEMA = output_schema()
# The per-atom columns of fix contacts/mn in order: counts.txt's header names them by number
# (f_c[1] ...). The cumulative ones grow over the counters' window; contacts_now is a count at
# one moment.
COUNTER_COLUMNS = SCHEMA["counters"]
CUMULATIVE_COUNTERS = tuple(name for name in COUNTER_COLUMNS if name != "contacts_now")
# the columns of energy.txt the analysis uses, by name (energy.txt's header names them; others
# are let be): the counters' sums over the group, the window's length
ENERGY_COLUMNS = ("step", "e_trans", "e_rot", "e_total", *COUNTER_COLUMNS, "window")
# the columns of fix contacts/mn's rows in order (contacts.txt, whose header names them f_c[1]
# ...)
ROW_COLUMNS = SCHEMA["rows"]
# the columns a row goes on with when the run booked energies (fix contacts/mn energy yes):
# read where the file has them
ROW_ENERGY_COLUMNS = SCHEMA["row_energy"]
# the codes of contacts.txt's kind column: a contact between two disks, of a disk with the
# boundary
CONTACT_KINDS = {name: int(code) for name, code in zip(SCHEMA["kinds"][0::2],
                                                       SCHEMA["kinds"][1::2])}

# The largest magnitude of a value the analysis takes: far beyond any energy, rate, time or count
# of a run, and small enough that the sums of squares its errors are made of stay finite in
# doubles (a square overflows above 1.3e154).
LARGEST = 1e150
NEGATIVE = "negative: it is an energy, a rate, a time fraction or a count"


def checked_values(values, where, non_negative=False):
    """values (numbers: an array, a list, or a table's rows) as an array of floats if each is
    one the analysis can average: finite, at most LARGEST in magnitude and, where non_negative
    (True, or one flag per column), not below 0. Else a DataError on the first that is not:
    where(*index) names it (a file's line and column, a summary's field). The one rule for the
    values of a run, whichever file (energy.txt, counts.txt, a summary) they come from."""
    values = np.asarray(values, dtype=float)
    finite = np.isfinite(values)
    huge = finite & (np.abs(np.where(finite, values, 0.0)) > LARGEST)
    negative = finite & np.asarray(non_negative) & (np.where(finite, values, 0.0) < 0)
    bad = ~finite | huge | negative
    if bad.any():
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        why = ("not a finite number" if not finite[index] else
               f"beyond {LARGEST:g} in magnitude, more than any energy, rate, time or count "
               "of a run (a damaged file?)" if huge[index] else NEGATIVE)
        raise DataError(f"{where(*index)} is {values[index]:g}, {why}")
    return values


def read_text(path):
    """A file's text (UTF-8); a byte that is not (a damaged or binary file) is a DataError
    naming the file and the line."""
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8")
    except UnicodeDecodeError as error:
        line = error.object[:error.start].count(b"\n") + 1
        raise DataError(f"{path}:{line}: byte 0x{error.object[error.start]:02x} is not UTF-8 "
                        "text: a damaged or binary file?") from None


def read_params(point):
    path = Path(point) / rundir.PARAMS
    if not path.exists():
        raise DataError(f"{path}: missing (the run did not start its outputs)")
    params, given = {}, {}
    for number, line in enumerate(read_text(path).splitlines(), 1):
        words = line.split()
        if len(words) != 2:
            raise DataError(f"{path}:{number}: expected 'name value', got {line!r}")
        name, value = words
        if name in given:
            raise DataError(f"{path}:{number}: {name} given twice (line {given[name]} gives it "
                            "too): which value the run took cannot be told")
        given[name] = number
        try:
            params[name] = float(value)
        except ValueError:
            params[name] = value
    return checked_params(params, path)


def checked_params(params, path):
    """params (name: number or word) if it has every value the analysis needs, each a number
    in its range; else a DataError naming `path`, where they came from."""
    for name in ("scene", "kn", "dt", "tau_c", "tau_w", "average_start", "run_time", "n_mobile"):
        if name not in params:
            raise DataError(f"{path}: no {name}")
    for name in ("kn", "dt", "tau_c", "tau_w", "average_start", "run_time", "n_mobile"):
        value = params[name]
        if not isinstance(value, float) or not np.isfinite(value) or \
                value < 0 or (value == 0 and name != "average_start"):
            bound = ">= 0" if name == "average_start" else "> 0"
            raise DataError(f"{path}: {name} = {value!r} must be a finite number {bound}")
    return params


def numbers(path, number, words):
    """The words of one line as floats, or a DataError naming the file and the line."""
    try:
        return [float(w) for w in words]
    except ValueError:
        raise DataError(f"{path}:{number}: not a number in {' '.join(words)!r}")


def numeric_table(path, columns, comment="#", non_negative=()):
    """Rows of whitespace-separated numbers with exactly len(columns) fields, as a dict of
    arrays. A short, long or non-numeric line is an error naming its line number, and so is a
    value checked_values refuses (the columns named in non_negative may not be negative)."""
    path = Path(path)
    if not path.exists():
        raise DataError(f"{path}: missing")
    rows, numbers_at = [], []
    for number, line in enumerate(read_text(path).splitlines(), 1):
        if not line.strip() or line.lstrip().startswith(comment):
            continue
        words = line.split()
        if len(words) != len(columns):
            raise DataError(f"{path}:{number}: {len(words)} columns, expected {len(columns)} "
                            f"({' '.join(columns)}): truncated or corrupt line?")
        rows.append(numbers(path, number, words))
        numbers_at.append(number)
    if not rows:
        raise DataError(f"{path}: no data")
    data = checked_values(rows, lambda row, column: f"{path}:{numbers_at[row]}: {columns[column]}",
                          [name in non_negative for name in columns])
    return {name: data[:, k] for k, name in enumerate(columns)}


def header_columns(path, first, needed):
    """The column names of a table from its own header: the last comment line whose first name
    is `first` ("# step e_trans ..."). Every name in `needed` must be there."""
    path = Path(path)
    if not path.exists():
        raise DataError(f"{path}: missing")
    names = None
    for line in read_text(path).splitlines():
        words = line.lstrip("#").split()
        if line.startswith("#") and words[:1] == [first]:
            names = tuple(words)
        elif line.strip() and not line.startswith("#"):
            break
    if names is None:
        raise DataError(f"{path}: no header line '# {first} ...' naming the columns")
    missing = [n for n in needed if n not in names]
    if missing:
        raise DataError(f"{path}: the header names no column {', '.join(missing)}")
    return names


def read_energy(point, params):
    """energy.txt (columns as its header names them) with a time column (step * dt)."""
    path = Path(point) / rundir.ENERGY
    # every column the analysis uses is a step, an energy, a count or a time: none below 0
    table = numeric_table(path, header_columns(path, "step", ENERGY_COLUMNS),
                          non_negative=ENERGY_COLUMNS)
    table["time"] = table["step"] * params["dt"]
    if len(table["time"]) < 2:
        raise DataError(f"{path}: 1 data row, the analysis needs at least 2: truncated?")
    if np.any(np.diff(table["step"]) <= 0):
        raise DataError(f"{Path(point) / rundir.ENERGY}: steps do not increase")
    return table


def read_dump_atoms(path, needed):
    """The single snapshot of a LAMMPS text dump (write_dump), its columns named by its own
    header; every name in `needed` must be there."""
    path = Path(path)
    if not path.exists():
        raise DataError(f"{path}: missing")
    lines = read_text(path).splitlines()
    try:
        start = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
        count = int(lines[lines.index("ITEM: NUMBER OF ATOMS") + 1])
    except (StopIteration, ValueError, IndexError):
        raise DataError(f"{path}: not a LAMMPS dump snapshot")
    columns = lines[start].split()[2:]
    missing = [n for n in needed if n not in columns]
    if missing:
        raise DataError(f"{path}: the header {' '.join(columns)} names no column "
                        f"{', '.join(missing)}")
    body = lines[start + 1:]
    if len(body) != count:
        raise DataError(f"{path}: {len(body)} atoms, the header says {count}: truncated?")
    rows = []
    for number, line in enumerate(body, start + 2):
        words = line.split()
        if len(words) != len(columns):
            raise DataError(f"{path}:{number}: {len(words)} columns, expected {len(columns)}")
        rows.append(numbers(path, number, words))
    data = np.array(rows)
    return {name: data[:, k] for k, name in enumerate(columns)}


def read_counts(point):
    """counts.txt: id, diameter and the counters of fix contacts/mn per disk, by name."""
    fix_columns = {f"f_c[{k}]": name for k, name in enumerate(COUNTER_COLUMNS, 1)}
    path = Path(point) / rundir.COUNTS
    table = read_dump_atoms(path, ("id", "diameter", *fix_columns))
    for name in ("id", "diameter", *fix_columns):     # ids, a size, counts and times
        checked_values(table[name], lambda row: f"{path}: atom {row + 1} of the snapshot: {name}",
                       non_negative=True)
    return {fix_columns.get(name, name): values for name, values in table.items()}


def profile_block(path, lines, start=1):
    """One fix ave/chunk block (header 'step chunks count', then the bins): bin centre, count,
    density, vx, vy as a 2D array."""
    if not lines:
        raise DataError(f"{path}: no data")
    try:
        step, nchunks, _ = lines[0].split()
        nchunks = int(nchunks)
    except ValueError:
        raise DataError(f"{path}: the block header {lines[0]!r} is not 'step chunks count'")
    body = lines[1:]
    if len(body) != nchunks:
        raise DataError(f"{path}: {len(body)} bins, the header says {nchunks}: truncated?")
    data = []
    for number, line in enumerate(body, start + 1):
        words = line.split()
        if len(words) != 6:
            raise DataError(f"{path}: bin line {line!r} does not have 6 columns")
        data.append(numbers(path, number, words[1:]))
    return np.array(data)


def read_profile(point):
    """profile.txt (fix ave/chunk, one block): bin centre, count, density, vx, vy. A run with
    checkpoints writes profile_chunks.txt instead: one block per chunk of the span, headed by
    '# chunk START END SAMPLES'; the span's profile is their mean weighted by SAMPLES (each
    block is a running average over its SAMPLES samples; a bin a block lacks counts as 0)."""
    path = Path(point) / rundir.PROFILE
    chunks = Path(point) / rundir.PROFILE_CHUNKS
    if not path.exists() and chunks.exists():
        blocks, weights = [], []
        for line in read_text(chunks).splitlines():
            if line.startswith("# chunk"):
                blocks.append([])
                weights.append(float(line.split()[4]))
            elif line.strip() and blocks:
                blocks[-1].append(line)
        if not blocks:
            raise DataError(f"{chunks}: no chunk")
        arrays = [profile_block(chunks, block) for block in blocks]
        longest = max(arrays, key=len)
        total = np.zeros_like(longest)
        for array, weight in zip(arrays, weights):
            total[:len(array), 1:] += weight * array[:, 1:]
        total[:, 1:] /= sum(weights)
        total[:, 0] = longest[:, 0]
        data = total
    elif not path.exists():
        raise DataError(f"{path}: missing")
    else:
        lines = [l for l in read_text(path).splitlines() if l.strip() and not l.startswith("#")]
        data = profile_block(path, lines)
    return {"y": data[:, 0], "count": data[:, 1], "density": data[:, 2], "vx": data[:, 3],
            "vy": data[:, 4]}


def read_rows(point):
    """contacts.txt (dump local of fix contacts/mn) as a dict of arrays, its columns named by
    each snapshot's own header (ITEM: ENTRIES f_c[1] ...); empty if none. The energy columns
    (ROW_ENERGY_COLUMNS) too where the first header names them (a run with energies = yes),
    then every header must."""
    path = Path(point) / rundir.ROWS
    if not path.exists():
        raise DataError(f"{path}: missing (run the deck with -var rows yes)")
    fix_columns = {f"f_c[{k}]": name for k, name in enumerate(ROW_COLUMNS, 1)}
    rows, columns, first_header = [], None, True
    for number, line in enumerate(read_text(path).splitlines(), 1):
        if line.startswith("ITEM:"):
            columns = None
            if line.startswith("ITEM: ENTRIES"):
                names = line.split()[2:]
                if first_header:
                    first_header = False
                    energy = {f"f_c[{k}]": name for k, name in
                              enumerate(ROW_ENERGY_COLUMNS, len(ROW_COLUMNS) + 1)}
                    if all(n in names for n in energy):
                        fix_columns.update(energy)
                missing = [n for n in fix_columns if n not in names]
                if missing:
                    raise DataError(f"{path}:{number}: the header {' '.join(names)} names no "
                                    f"column {', '.join(missing)}")
                columns = [names.index(n) for n in fix_columns]
                width = len(names)
            continue
        if columns is None:
            continue
        words = line.split()
        if len(words) != width:
            raise DataError(f"{path}:{number}: {len(words)} columns, the header names {width}")
        values = numbers(path, number, words)
        rows.append([values[k] for k in columns])
    data = np.array(rows).reshape(-1, len(fix_columns))
    return {name: data[:, k] for k, name in enumerate(fix_columns.values())}


def read_trajectory(point):
    return numeric_table(Path(point) / rundir.TRAJECTORY, ("time", "x", "y", "vx", "vy"))


def read_stopped(point):
    """The time at which the run ended early because its pile had stopped (stopped.txt, written
    by inputs/lib/run.lmp), or None for a run that went on to run_time."""
    path = Path(point) / rundir.STOPPED
    if not path.exists():
        return None
    words = read_text(path).split()
    if len(words) != 2 or words[0] != "stopped_at":
        raise DataError(f"{path}: expected 'stopped_at TIME', got {' '.join(words)!r}")
    return numbers(path, 1, words[1:])[0]


def read_variables(point):
    """point.json: the point's scene and deck variables, as the sweep runner wrote them: the
    run's identity (rundir), which its directory's name must give."""
    point = Path(point)
    path = point / rundir.POINT
    if not path.exists():
        raise DataError(f"{path}: missing (not a sweep's point)")
    try:
        variables = json.loads(read_text(path), object_pairs_hook=unique_keys(path))
    except ValueError as error:
        raise DataError(f"{path}: not valid JSON ({error})")
    return checked_name(checked_variables(variables, path),
                        f"{point.parent.name}/{point.name}", path, "its directory")


def unique_keys(path):
    """json.loads' object_pairs_hook that refuses an object naming a key twice (JSON's own
    reader would keep the last, silently): a DataError naming `path` and the key."""
    def hook(pairs):
        seen = set()
        for key, _ in pairs:
            if key in seen:
                raise DataError(f"{path}: {key} given twice: which value is meant cannot be told")
            seen.add(key)
        return dict(pairs)
    return hook


def checked_variables(variables, path):
    """variables if they are an object of deck variables, each a number or a word (what the
    sweep runner passes to the deck: the analysis groups the runs by them); else a DataError
    naming `path`, where they came from."""
    if not isinstance(variables, dict):
        raise DataError(f"{path}: expected an object of deck variables")
    for name, value in variables.items():
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise DataError(f"{path}: variable {name} is {value!r}, not a number or a word")
    return variables


def checked_name(variables, name, variables_from, named_by):
    """variables if they give the run the name (<scene>/<point>) that `named_by`, its
    directory or summary file, gives it: the runner names a point's directory, and summarize
    its summary, after the variables (rundir.run_name), so a name that says otherwise is a
    renamed directory or file, or the variables of another run. Else a DataError naming
    both."""
    if "scene" not in variables:
        raise DataError(f"{variables_from}: no scene (the sweep runner writes each point's)")
    given = rundir.run_name(variables)
    if name != given:
        raise DataError(f"{variables_from} gives the run {given}, but {named_by} names it "
                        f"{name}: they disagree (renamed, or the variables of another run?)")
    return variables


def same_value(variable, param):
    """Whether a deck variable (point.json's: a number or a word) and params.txt's value of it
    (a float, or a word) are one value: equal as numbers where both are, else as words."""
    try:
        return float(variable) == float(param)
    except (TypeError, ValueError):
        return str(variable) == str(param)


def checked_agreement(variables, params, variables_from, params_from):
    """params if every variable that params names too has the same value there (same_value):
    the deck prints into params.txt the variables the runner passed it (point.json), so where
    they differ the outputs are not those of this point's run, or a file was edited. Else a
    DataError naming both sources (variables_from, params_from) and the variable."""
    for name in sorted(set(variables) & set(params)):
        if not same_value(variables[name], params[name]):
            raise DataError(f"{variables_from} gives {name} = {variables[name]!r}, but "
                            f"{params_from} gives {params[name]!r}: they disagree (the outputs "
                            "of another run, or an edited file?)")
    return params


class Point:
    """A point directory's outputs, each file read once, when first asked for (the large
    optional ones, rows, trajectory and profile, only then); a file that cannot be read raises
    its DataError each time it is asked for."""

    def __init__(self, directory):
        self.directory = Path(directory)

    timing = cached_property(lambda self: rundir.read_timing(self.directory))
    ending = cached_property(lambda self: rundir.ending(self.directory, self.timing))
    variables = cached_property(lambda self: read_variables(self.directory))
    params = cached_property(lambda self: read_params(self.directory))
    stopped_at = cached_property(lambda self: read_stopped(self.directory))
    energy = cached_property(lambda self: read_energy(self.directory, self.params))
    counts = cached_property(lambda self: read_counts(self.directory))
    rows = cached_property(lambda self: read_rows(self.directory))
    trajectory = cached_property(lambda self: read_trajectory(self.directory))
    profile = cached_property(lambda self: read_profile(self.directory))
