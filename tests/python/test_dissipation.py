"""Where the energy goes (postprocess/dissipation.py, durations.dissipation_split; the rule of
docs/hard_sphere_limit.md, "Where the energy goes"): the classification of contacts into
lasting, multiple and binary ones, the shares of the dissipated energy, and the rule's verdict
on series whose answer is known."""
import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

from postprocess.dissipation import analyse_dissipation, per_kn
from postprocess.durations import DISSIPATION_NAMES, dissipation_split, multiple_contacts
from postprocess.io import CONTACT_KINDS, DataError
from postprocess.summary import read_summary

DISK, BOUNDARY = CONTACT_KINDS["disk"], CONTACT_KINDS["boundary"]
WIDE = Path(__file__).resolve().parents[2] / "data" / "confirm_frictional_wide"


def rows(*contacts):
    """Rows from (id_i, id_j, kind, start, duration, dissipated, dissipated_sliding)."""
    table = np.array(contacts, dtype=float).reshape(-1, 7)
    names = ("id_i", "id_j", "kind", "start", "duration", "dissipated", "dissipated_sliding")
    return {name: table[:, k] for k, name in enumerate(names)}


def test_a_contact_is_multiple_when_it_overlaps_another_of_one_of_its_particles():
    """Overlap is per particle and in time: two contacts of disk 1 that overlap are both
    multiple, whichever of them is the pair's i; a contact that only touches another in time
    (one ends as the next begins) is not; nor one whose partner's other contact is a wall
    contact of another disk; a boundary contact's id_j is not a particle."""
    found = multiple_contacts(rows(
        (1, 2, DISK, 0.0, 1.0, 0, 0),        # overlaps the next through disk 1
        (3, 1, DISK, 0.5, 1.0, 0, 0),        # disk 1 as j
        (1, 4, DISK, 2.0, 1.0, 0, 0),        # alone
        (4, 5, DISK, 3.0, 0.5, 0, 0),        # touches the previous one at t = 3 through disk 4
        (6, 1, BOUNDARY, 0.0, 5.0, 0, 0),    # disk 6 against the wall: id_j is no disk
        (7, 8, DISK, 10.0, 1.0, 0, 0),       # disk 7 ...
        (7, 0, BOUNDARY, 9.0, 5.0, 0, 0)))   # ... on the wall the whole time
    assert found.tolist() == [True, True, False, False, False, True, True]


def test_the_shares_add_up_and_follow_the_contacts_durations():
    """A lasting contact (over 3 binary durations), a multiple pair of short ones and a binary
    collision: each share is its contacts' energy over D; lasting + binary + the multiple short
    ones = 1; contacts that ended outside the window count nowhere; the negative sliding work
    is its own (negative) share and counted per contact."""
    tau_c, tau_w = 0.1, 0.2
    split = dissipation_split(rows(
        (1, 2, DISK, 10.0, 0.5, 4.0, 1.0),          # lasting (5 tau_c)
        (3, 4, DISK, 11.0, 0.1, 1.0, -0.5),         # multiple with the next, short
        (4, 5, DISK, 11.05, 0.1, 2.0, 0.0),
        (6, 0, BOUNDARY, 12.0, 0.5, 3.0, 0.0),      # 2.5 tau_w: binary against the wall
        (7, 8, DISK, 30.0, 0.1, 100.0, 0.0),        # ended after the window
        (8, 9, DISK, 1.0, 0.1, 100.0, 0.0)),        # ended before it
        tau_c, tau_w, start=5.0, stop=20.0)
    assert split["dissipated"] == pytest.approx(10.0)
    assert split["lasting"] == pytest.approx(0.4)
    assert split["multiple"] == pytest.approx(0.3)
    assert split["binary"] == pytest.approx(0.3)
    assert split["sliding"] == pytest.approx(0.05)
    assert split["negative_sliding"] == pytest.approx(-0.05)
    assert split["negative_sliding_contacts"] == 1 and split["contacts"] == 4


def record(scene, law, kn, seed, lasting, ended="flowing"):
    """A record of a run whose contacts lost `lasting` of D in lasting contacts."""
    dissipation = {name: 0.0 for name in DISSIPATION_NAMES}
    dissipation.update(dissipated=100.0, lasting=lasting, multiple=lasting + 0.1,
                       binary=0.9 - lasting, contacts=1000, negative_sliding_contacts=3,
                       global_dissipated=101.0)
    return SimpleNamespace(scene=scene, point=Path(f"{scene}/kn{kn:g}_s{seed}"), ended=ended,
                           cpu_seconds=None,
                           stopped_at=None, params={"kn": kn, "tangential": law},
                           variables={"rows_time": 50}, measured={"contacts": {
                               "dissipation": dissipation}})


KN = [1.6e6 * 4 ** p for p in range(5)]


@pytest.mark.parametrize("share,verdict", [
    (lambda kn, noise: 0.3 * (1 + noise), "finite"),
    (lambda kn, noise: 0.3 * (kn / KN[0]) ** -0.5 * (1 + noise), "vanishing")],
    ids=["steady share", "share as k_n^-1/2"])
def test_the_rule_tells_a_lasting_share_that_stays_from_one_that_vanishes(share, verdict):
    """The rule's two answers on series built to have them (scatter 5 % between seeds): a share
    that stays at 0.3 is finite, one that falls as k_n^-1/2 vanishing; a stopped run is left
    out of its series and said to be."""
    rng = np.random.default_rng(5)
    records = [record("frictional_flow", "literal", kn, seed, share(kn, rng.normal(0, 0.05)))
               for kn in KN for seed in range(4)]
    records.append(record("frictional_flow", "literal", KN[0], 9, 0.3, ended="stopped"))
    (group,) = analyse_dissipation(records, samples=300)
    assert group.decision.verdict == verdict, group.decision.why
    assert [why for _, why in group.left_out] == ["it ended stopped"]
    assert [runs for _, runs, *_ in per_kn(group)] == [4] * 5


def test_a_summary_keeps_the_dissipation_and_refuses_a_count_that_is_not_one(tmp_path):
    """The shares survive the summary (the committed data the rule is judged on); a damaged
    count is refused by name."""
    source = next((WIDE / "frictional_flow").glob("*.json"))
    data = json.loads(source.read_text())
    block = {name: 0.25 for name in DISSIPATION_NAMES}
    block.update(contacts=40, negative_sliding_contacts=2)
    data["measured"]["contacts"]["dissipation"] = block
    path = tmp_path / "frictional_flow" / source.name
    path.parent.mkdir()
    path.write_text(json.dumps(data))
    kept = read_summary(path, selection=None).measured["contacts"]["dissipation"]
    assert kept == block
    block["contacts"] = 2.5
    path.write_text(json.dumps(data))
    with pytest.raises(DataError, match=r"measured\.contacts\.dissipation\.contacts is 2\.5, "
                       "not a count"):
        read_summary(path, selection=None)
