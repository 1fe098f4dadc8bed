"""The output schema (plugin/mn_output_schema.h, copied by `mn-law --columns` into
postprocess/output_schema.txt; tests/lammps/test_mn_law_columns.py checks the copy) against the
texts that cannot take it from the header: the decks' titles and columns, the docs' lists. And
the readers, which read the columns by the files' own headers: a column they do not need (one
that a later version adds) does not stop them."""
import re
from pathlib import Path

from postprocess.io import (COUNTER_COLUMNS, CONTACT_KINDS, ENERGY_COLUMNS, ROW_COLUMNS, SCHEMA,
                            read_counts, read_energy, read_rows)

ROOT = Path(__file__).resolve().parents[2]
LIGGGHTS_CHUTE = ROOT / "inputs" / "liggghts" / "chute_3d.lmp"
ENERGY_DECKS = (ROOT / "inputs" / "lib" / "energy.lmp", LIGGGHTS_CHUTE)
COUNTS_DECKS = (ROOT / "inputs" / "lib" / "run.lmp", LIGGGHTS_CHUTE)


def fix_columns(text):
    """The numbers k of the f_c[k] a deck's line names, in order."""
    return [int(k) for k in re.findall(r"f_c\[(\d+)\]", text)]


def test_the_energy_titles_name_the_counters_the_lines_print():
    """energy.txt's header (fix print's title, which this LAMMPS writes as given: no variable can
    fill it) names fix contacts/mn's global vector entries in the schema's order, as many as the
    line prints. A title that swapped two counters, or a line that printed one more or fewer,
    would file a count under another's name."""
    for deck in ENERGY_DECKS:
        lines = [line for line in deck.read_text().splitlines()
                 if "fix energy all print" in line and "f_c[" in line]
        counters = [line for line in lines if "dissipated" not in line]
        assert len(counters) == 1, deck
        values, title = re.fullmatch(r".*print \S+ (['\"])(.*?)\1 .* title (['\"])# (.*?)\3.*",
                                     counters[0]).group(2, 4)
        names = title.split()
        assert names[:4] == ["step", "e_trans", "e_rot", "e_total"], deck
        assert names[4:] == [*COUNTER_COLUMNS, SCHEMA["vector_extras"][0]], deck
        assert fix_columns(values) == list(range(1, len(names) - 3)), deck
        assert set(ENERGY_COLUMNS) <= set(names), deck
    # energies = yes (LAMMPS's decks): the same, then the energy sums under the schema's names,
    # after the global vector's extras (window, group_size: f_c[9] on), then the deck's own
    lines = [line for line in ENERGY_DECKS[0].read_text().splitlines()
             if "fix energy all print" in line and "dissipated" in line]
    assert len(lines) == 1
    values, title = re.fullmatch(r".*print \S+ (['\"])(.*?)\1 .* title (['\"])# (.*?)\3.*",
                                 lines[0]).group(2, 4)
    names = title.split()
    first = len(COUNTER_COLUMNS) + len(SCHEMA["vector_extras"]) + 1
    energy_names = SCHEMA["energy_sums"]
    assert names[:4 + len(COUNTER_COLUMNS) + 1] == [
        "step", "e_trans", "e_rot", "e_total", *COUNTER_COLUMNS, SCHEMA["vector_extras"][0]]
    assert names[4 + len(COUNTER_COLUMNS) + 1:] == [*energy_names, "e_gravity", "e_budget"]
    assert fix_columns(values) == [*range(1, len(COUNTER_COLUMNS) + 2),
                                   *range(first, first + len(energy_names))]


def test_the_dumps_write_every_column_of_the_schema():
    """counts.txt has every per-atom counter and contacts.txt every row column, in the fix's
    order (the readers name them by that order)."""
    for deck in COUNTS_DECKS:
        lines = [line for line in deck.read_text().splitlines() if "counts.txt" in line
                 and "write_dump" in line]
        assert len(lines) == 1, deck
        assert fix_columns(lines[0]) == list(range(1, len(COUNTER_COLUMNS) + 1)), deck
    rows = [line for line in (ROOT / "inputs" / "lib" / "outputs.lmp").read_text().splitlines()
            if "contacts.txt" in line and "dump rows" in line]
    assert len(rows) == 2    # with energies = yes, and without
    with_energy = [line for line in rows if f"f_c[{len(ROW_COLUMNS) + 1}]" in line]
    assert len(with_energy) == 1
    assert fix_columns(with_energy[0]) == list(range(1, len(ROW_COLUMNS) +
                                                    len(SCHEMA["row_energy"]) + 1))
    rows.remove(with_energy[0])
    assert fix_columns(rows[0]) == list(range(1, len(ROW_COLUMNS) + 1))


def test_the_docs_name_the_columns_and_variables_in_order():
    """docs/fix_contacts_mn.rst's numbered lists name the counters and the row columns in the
    schema's order, and the kinds' codes; docs/pair_gran_mn.rst lists the published variables."""
    page = (ROOT / "docs" / "fix_contacts_mn.rst").read_text()
    listed = re.findall(r"^(\d+)\. ``(\w+)``", page, re.MULTILINE)
    names = [name for _, name in listed]
    energy_columns, row_energy = SCHEMA["energy_sums"][:-1], SCHEMA["row_energy"]
    assert names == [*COUNTER_COLUMNS, *ROW_COLUMNS, *energy_columns, *row_energy]
    assert [int(n) for n, _ in listed] == [
        *range(1, len(COUNTER_COLUMNS) + 1), *range(1, len(ROW_COLUMNS) + 1),
        *range(len(COUNTER_COLUMNS) + 1, len(COUNTER_COLUMNS) + len(energy_columns) + 1),
        *range(len(ROW_COLUMNS) + 1, len(ROW_COLUMNS) + len(row_energy) + 1)]
    assert f"``{SCHEMA['energy_sums'][-1]}``" in page
    kinds = re.search(r"``kind``: (.*)", page).group(1)
    assert re.findall(r"``(\w+)`` (\d+)", kinds) == [(k, str(c)) for k, c in CONTACT_KINDS.items()]
    for extra in SCHEMA["vector_extras"]:
        assert f"``{extra}``" in page, extra
    pair = (ROOT / "docs" / "pair_gran_mn.rst").read_text()
    published = re.search(r"variables that a deck may use:\s*(.*?)\(e\.g\.", pair, re.DOTALL)
    assert re.findall(r"\*(mn_\w+)\*", published.group(1)) == list(SCHEMA["published"])


def write_dump(path, columns, rows):
    path.write_text("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n" f"{len(rows)}\n"
                    "ITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n"
                    f"ITEM: ATOMS {' '.join(columns)}\n" +
                    "".join(" ".join(map(str, row)) + "\n" for row in rows))


def test_the_readers_take_columns_by_header_and_let_others_be(tmp_path):
    """A file with one more column than the analysis needs (f_c[9] of a row, f_c[7] of a count,
    an energy column after window) reads as one without: each column by its header's name. A
    reader that took columns by position, or required exactly the known ones, would misname or
    refuse it."""
    (tmp_path / "params.txt").write_text("scene frictional_flow\nkn 1\ndt 0.5\ntau_c 1\ntau_w 1\n"
                                         "average_start 0\nrun_time 1\nn_mobile 2\n")
    names = ["step", "e_trans", "e_rot", "e_total", *COUNTER_COLUMNS, "window", "e_stored"]
    (tmp_path / "energy.txt").write_text(
        "# " + " ".join(names) + "\n" +
        "".join(" ".join(str(k + line) for k in range(len(names))) + "\n" for line in (0, 1)))
    energy = read_energy(tmp_path, {"dt": 0.5})
    assert energy["window"].tolist() == [10, 11] and energy["e_stored"].tolist() == [11, 12]
    assert energy["time"].tolist() == [0.0, 0.5]

    counters = [f"f_c[{k}]" for k in range(1, len(COUNTER_COLUMNS) + 2)]
    write_dump(tmp_path / "counts.txt", ["id", *counters, "diameter"],
               [[1, *range(10, 10 + len(counters)), 1.0]])
    counts = read_counts(tmp_path)
    for k, name in enumerate(COUNTER_COLUMNS):
        assert counts[name].tolist() == [10 + k], name

    extra = len(ROW_COLUMNS) + 1
    header = "ITEM: ENTRIES " + " ".join(f"f_c[{k}]" for k in (extra, *range(1, extra)))
    row = [99.0, *range(1, extra)]
    (tmp_path / "contacts.txt").write_text(
        "ITEM: TIMESTEP\n10\nITEM: NUMBER OF ENTRIES\n1\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n"
        f"0 1\n{header}\n" + " ".join(map(str, row)) + "\n")
    rows = read_rows(tmp_path)
    assert [rows[name].tolist() for name in ROW_COLUMNS] == \
        [[float(k)] for k in range(1, len(ROW_COLUMNS) + 1)]
    assert set(rows) == set(ROW_COLUMNS)    # f_c[9] alone is not the energy columns

    # a run with energies = yes: its rows' energy columns too, by name
    width = len(ROW_COLUMNS) + len(SCHEMA["row_energy"])
    header = "ITEM: ENTRIES " + " ".join(f"f_c[{k}]" for k in range(1, width + 1))
    (tmp_path / "contacts.txt").write_text(
        "ITEM: TIMESTEP\n10\nITEM: NUMBER OF ENTRIES\n1\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n"
        f"0 1\n{header}\n" + " ".join(str(k) for k in range(1, width + 1)) + "\n")
    rows = read_rows(tmp_path)
    assert [rows[name].tolist() for name in (*ROW_COLUMNS, *SCHEMA["row_energy"])] == \
        [[float(k)] for k in range(1, width + 1)]
