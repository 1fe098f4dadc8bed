"""LIGGGHTS's `model mn` publishes the variables of the output schema (plugin/mn_output_schema.h,
postprocess/output_schema.txt), as pair_style gran/mn does, with the law's values for spheres:
the minimal input of docs/liggghts.md, its run cut to `run 0`, prints each. A name the model did
not define stops the input (LIGGGHTS: variable not defined); a value of another law or shape
differs in its leading digits (mn-law's to 1e-12: the same header, compiled with other flags)."""
import re

import pytest

from granmn_run import law
from liggghts_decks import LIGGGHTS, run_liggghts
from postprocess.io import SCHEMA
from test_minimal_input import documented_input

pytestmark = pytest.mark.skipif(not LIGGGHTS,
                                reason="LIGGGHTS was not built (GRANMN_LIGGGHTS unset)")


def test_the_model_publishes_the_schemas_variables(tmp_path):
    text = documented_input()
    material = [float(re.search(rf"^fix \S+ all property/global {name} peratomtypepair 1 (\S+)$",
                                text, re.M).group(1))
                for name in ("normalStiffnessPerMass", "coefficientRestitution",
                             "coefficientTangentialRestitution")]
    names = SCHEMA["published"]
    deck = re.sub(r"^run \d+$", "run 0", text, flags=re.M) + \
        f"print \"RESULT published {' '.join(f'${{{name}}}' for name in names)}\"\n"
    _, out = run_liggghts(deck, tmp_path)
    printed = re.search(r"^RESULT published (.*)$", out, re.M).group(1).split()
    derived = law(*material, shape="sphere")
    assert len(printed) == len(names)
    for name, value in zip(names, printed):
        assert float(value) == pytest.approx(derived[name[len("mn_"):]], rel=1e-12), name
