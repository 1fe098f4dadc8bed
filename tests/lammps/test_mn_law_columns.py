"""`mn-law --columns` prints the output schema of plugin/mn_output_schema.h; the post-processing
reads its copy, postprocess/output_schema.txt (tests/python/test_output_schema.py checks the
decks and docs against that copy). And pair_style gran/mn defines every variable the schema says
it publishes, with mn-law's value of it."""
import subprocess
from pathlib import Path

import pytest

from granmn_run import BUILD_PATHS, law, run_lammps
from postprocess.io import SCHEMA, output_schema

MN_LAW = BUILD_PATHS.mn_law
COPY = Path(__file__).resolve().parents[2] / "postprocess" / "output_schema.txt"


def test_the_post_processing_reads_the_headers_schema(tmp_path):
    """The copy's tables are mn-law's, line for line: a column added to, dropped from or moved in
    the header without the copy's following would make the analysis misname it."""
    printed = subprocess.run([str(MN_LAW), "--columns"], capture_output=True, text=True,
                             check=True).stdout
    (tmp_path / "printed.txt").write_text(printed)
    assert output_schema(tmp_path / "printed.txt") == output_schema(COPY), \
        f"postprocess/output_schema.txt differs from `{MN_LAW} --columns`: copy its output there"
    copied = [line for line in COPY.read_text().splitlines() if not line.startswith("#")]
    assert printed.splitlines() == copied


def test_the_pair_style_publishes_the_schemas_variables(tmp_path):
    """Each published variable is defined once the pair style is given, with the value mn-law
    derives for it (mn-law prints the same values under the names less mn_): a name the pair
    style did not define would stop the deck (LAMMPS: variable not defined), a value of another
    law differs in its leading digits."""
    names = SCHEMA["published"]
    deck = f"""
region box block 0 10 0 10 -0.5 0.5
create_box 1 box
create_atoms 1 single 5 5 0
pair_style gran/mn kn 2e5 e 0.7 beta 0.7 mu 0.5
pair_coeff * *
print "RESULT published {' '.join(f'$(v_{name}:%.17g)' for name in names)}"
"""
    printed = run_lammps(deck, tmp_path).result("published")
    derived = law(2e5, 0.7, 0.7)
    assert len(printed) == len(names)
    for name, value in zip(names, printed):
        assert value == pytest.approx(derived[name[len("mn_"):]], rel=1e-12), name
