"""bench/peer_chute.py's decks from LAMMPS's bench/in.chute, written with tabs (LAMMPS 2021) or
spaces (2025 on): every variant edited as meant in both, and a deck it was not written for
refused with a message instead of run unedited."""
import re

import pytest

from bench import peer_chute

# the commands of LAMMPS's bench/in.chute that the variants edit, in its order
SHIPPED = """units\t\tlj
atom_style\tsphere
boundary\tp p fs
newton\t\toff
comm_modify\tvel yes
read_data\tdata.chute
pair_style\tgran/hooke/history 200000.0 NULL 50.0 NULL 0.5 0
pair_coeff\t* *
neighbor\t0.1 bin
neigh_modify\tevery 1 delay 0
group\t\tbottom type 2
group\t\tactive subtract all bottom
neigh_modify\texclude group bottom bottom
fix\t\t3 active nve/sphere
thermo\t\t100
run\t\t100
"""
MN = "pair_style gran/mn kn 1 e 0.9 beta 1 mu 0.5 coulomb_cutback wall_types 2"


def commands(deck):
    return [" ".join(line.split()) for line in deck.splitlines() if line.strip()]


@pytest.mark.parametrize("shipped", [SHIPPED, re.sub(r"\t+", "    ", SHIPPED)],
                         ids=["tabs", "spaces"])
def test_each_variant_is_the_shipped_deck_with_its_own_edits(shipped):
    decks = {name: commands(peer_chute.deck_text("P.so", deck, 50))
             for name, deck in peer_chute.variants(shipped, MN).items()}
    hooke = decks["gran/hooke/history"]
    assert hooke[0] == "plugin load P.so"
    assert hooke[1:] == [c for c in commands(SHIPPED) if c not in ("thermo 100", "run 100")] + \
        ["thermo 50", "run 50"]
    assert "pair_style gran/hooke/history 200000.0 NULL 50.0 NULL 0.5 0" in hooke
    mn = decks["gran/mn"]
    assert MN in mn and "pair_coeff * *" in mn and "comm_modify vel yes" in mn
    assert not [c for c in mn if "gran/hooke" in c or "exclude" in c]
    assert decks["gran/mn, comm_modify vel no"] == [c for c in mn if c != "comm_modify vel yes"]
    granular = decks["granular"]
    assert "pair_style granular" in granular and "pair_coeff * *" not in granular
    assert "neigh_modify exclude group bottom bottom" in granular
    assert [c for c in granular if c.startswith("pair_coeff")] == [
        "pair_coeff * * hooke 200000.0 50.0 tangential linear_history 57142.85714285714 0 0.5 "
        "damping mass_velocity"]
    for deck in decks.values():
        assert deck[-2:] == ["thermo 50", "run 50"]


@pytest.mark.parametrize("missing", ["neigh_modify\texclude group bottom bottom\n",
                                     "run\t\t100\n", "comm_modify\tvel yes\n"])
def test_a_deck_without_a_line_it_edits_is_refused(missing):
    with pytest.raises(SystemExit, match="not the deck it was written for"):
        for deck in peer_chute.variants(SHIPPED.replace(missing, ""), MN).values():
            peer_chute.deck_text("P.so", deck, 50)


def test_a_line_twice_is_refused():
    with pytest.raises(SystemExit, match="has 2 lines 'run 100'"):
        peer_chute.deck_text("P.so", SHIPPED + "run 100\n", 50)


def test_replicate_follows_the_read_data():
    """--replicate 2 2 1: the chute of 32000 spheres becomes 128000 before anything else acts
    on the atoms (the measurement of docs/performance.md's ghost velocities)."""
    deck = commands(peer_chute.deck_text("P.so", SHIPPED, 50, replicate=(2, 2, 1)))
    at = deck.index("read_data data.chute")
    assert deck[at + 1] == "replicate 2 2 1" and deck.count("replicate 2 2 1") == 1
    assert "replicate" not in " ".join(commands(peer_chute.deck_text("P.so", SHIPPED, 50)))
