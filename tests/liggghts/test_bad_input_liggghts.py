"""LIGGGHTS's `model mn tangential mn` refuses what it cannot do with an ERROR that names the
input (docs/bad_input.md lists each case): missing or asymmetric property/global values, e or
beta out of range, the models combined with others (cohesion, rolling friction, LIGGGHTS's
own tangential or normal models), for the pair style and for walls alike, and energies asked
for where they cannot be booked."""
import pytest

from liggghts_decks import LIGGGHTS, Particle, Scene, data_file, liggghts_deck, run_liggghts

pytestmark = pytest.mark.skipif(not LIGGGHTS, reason="LIGGGHTS was not built (GRANMN_LIGGGHTS unset)")


SCENE = Scene([Particle((-0.505, 0.0, 0.6)), Particle((0.505, 0.0, 0.6))], dt=1e-5, steps=10)


def deck(replace=(), wall=False, atom_types=1, dt=SCENE.dt, **law):
    """The two-sphere deck of the cross-checks, with the given text replacements, and its data
    file (with so many atom types)."""
    scene = Scene(SCENE.particles, dt, SCENE.steps, wall=wall, **law)
    text = liggghts_deck(scene)
    for old, new in replace:
        assert old in text, old
        text = text.replace(old, new)
    return text, data_file(scene, atom_types)

# what LIGGGHTS's hooke/stiffness reads, so that its own refusal does not come first
HOOKE_STIFFNESS = "".join(f"fix {name} all property/global {name} peratomtypepair 1 1.0\n"
                          for name in ("kn", "kt", "gamman", "gammat"))

BAD = {
    "LIGGGHTS: coefficientTangentialRestitution missing": (
        deck([("fix b all property/global coefficientTangentialRestitution peratomtypepair 1 0.7\n", "")]),
        "Could not locate a fix/property storing value(s) for coefficientTangentialRestitution as requested by model mn"),
    "LIGGGHTS: e above one": (deck(e=1.2), "model mn: for atom types 1 and 1: e must lie in (0,1]"),
    "LIGGGHTS: timestep above the stability limit": (
        deck(dt=0.01),
        "model mn: for atom types 1 and 1: timestep 0.01 exceeds the stability limit 0.00282"),
    "LIGGGHTS: beta zero": (deck(beta=0.0), "for atom types 1 and 1: beta must lie in (0,1]"),
    "LIGGGHTS: normalStiffnessPerMass negative": (
        deck(kn=-1.0), "for atom types 1 and 1: kn must be a finite number > 0"),
    "LIGGGHTS: coefficientFriction not symmetric (LIGGGHTS's own check)": (
        deck([("normalStiffnessPerMass peratomtypepair 1 200000.0", "normalStiffnessPerMass peratomtypepair 2 2e5 2e5 2e5 2e5"),
              ("coefficientRestitution peratomtypepair 1 0.7", "coefficientRestitution peratomtypepair 2 0.7 0.7 0.7 0.7"),
              ("coefficientTangentialRestitution peratomtypepair 1 0.7", "coefficientTangentialRestitution peratomtypepair 2 0.7 0.7 0.7 0.7"),
              ("coefficientFriction peratomtypepair 1 0.5", "coefficientFriction peratomtypepair 2 0.5 0.3 0.4 0.5")],
             atom_types=2),
        "Fix property/global (id m): per-atomtype property matrix must be symmetric"),
    "LIGGGHTS: model mn with tangential history": (
        deck([("model mn tangential mn", "model mn tangential history")]),
        "pair_style gran: model mn needs tangential mn"),
    "LIGGGHTS: tangential mn with model hooke/stiffness": (
        deck([("model mn tangential mn", "model hooke/stiffness tangential mn")],
             extra=HOOKE_STIFFNESS),
        "pair_style gran: tangential mn needs model mn"),
    "LIGGGHTS: model mn with a cohesion model": (
        deck([("model mn tangential mn", "model mn tangential mn cohesion sjkr")]),
        "pair_style gran: model mn takes no cohesion model"),
    "LIGGGHTS: model mn with rolling friction": (
        deck([("model mn tangential mn", "model mn tangential mn rolling_friction cdt")]),
        "pair_style gran: model mn takes no rolling_friction model"),
    "LIGGGHTS: fix contacts/mn energy yes without energy on": (
        deck([("fix integrate mobile nve/sphere\n",
               "fix integrate mobile nve/sphere\nfix c mobile contacts/mn energy yes\n")]),
        "fix contacts/mn energy yes: pair_style gran keeps no energy history per contact: add "
        "energy on after its models"),
    "LIGGGHTS: fix contacts/mn energy yes with a wall (fix wall/gran)": (
        deck(wall=True, energy=True),
        "fix contacts/mn energy yes: fix wall/gran with model mn cannot book its contacts' "
        "energies"),
    "LIGGGHTS: fix contacts/mn energy yes without an atom map": (
        deck([("atom_modify map array\n", "")], energy=True),
        "fix contacts/mn energy yes needs an atom map (atom_modify map array)"),
    "LIGGGHTS: fix contacts/mn energy neither yes nor no": (
        deck([("fix integrate mobile nve/sphere\n",
               "fix integrate mobile nve/sphere\nfix c mobile contacts/mn energy on\n")]),
        "Illegal fix contacts/mn command: energy needs yes or no"),
    "LIGGGHTS: wall with model mn and tangential history": (
        deck([("wall/gran model mn tangential mn", "wall/gran model mn tangential history")],
             wall=True),
        "fix floor wall/gran: model mn needs tangential mn"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_refused(tmp_path, case):
    (text, data), message = BAD[case]
    status, output = run_liggghts(text, tmp_path, data, check=False)
    assert status != 0, output[-2000:]
    assert "ERROR" in output and message in output, output[-2000:]


def test_an_error_of_one_process_reaches_the_output_and_the_log(tmp_path):
    """LIGGGHTS's Error::one (here: `surface multicontact` without the fix that model needs)
    wrote its message to the screen only and called MPI_Abort unflushed: to a pipe or a file,
    or with -screen none as the sweep runner runs it, the run ended with MPI's abort notice
    alone. plugin/liggghts/liggghts-3.8.0-errors.patch writes it to the log too, flushed; on
    LIGGGHTS as shipped both checks below fail."""
    text, data = deck([("model mn tangential mn", "model mn tangential mn surface multicontact")])
    message = "ERROR on proc 0: No suitable multicontact fix found"
    status, output = run_liggghts(text, tmp_path, data, check=False)
    assert status != 0 and message in output, output[-2000:]
    assert message in (tmp_path / "log.liggghts").read_text()
