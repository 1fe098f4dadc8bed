"""The same small scenes for LIGGGHTS 3.8 with `model mn tangential mn` (the project's build,
GRANMN_LIGGGHTS) and for lmp with the gran/mn plugin, and the runs of both.

A scene is a list of particles (position, velocity, spin, diameter, mass), an optional plane
wall below them (z = 0 in 3D, y = 0 in 2D), an optional gravity, and a number of steps; both
decks print each particle's state at the end as `RESULT state<id> x y z vx vy vz wx wy wz`."""
import os
import re
import subprocess
from dataclasses import dataclass, field
from pathlib import Path

from granmn_run import HEADER, MPIEXEC, PLUGIN, run_lammps
from postprocess.io import SCHEMA

LIGGGHTS = os.environ.get("GRANMN_LIGGGHTS", "")


@dataclass
class Particle:
    x: tuple
    v: tuple = (0.0, 0.0, 0.0)
    omega: tuple = (0.0, 0.0, 0.0)
    diameter: float = 1.0
    mass: float = 1.0
    fixed: bool = False     # a boundary particle (type 2): fix freeze in LIGGGHTS, wall_types 2
                            # of gran/mn; never integrated


@dataclass
class Scene:
    particles: list
    dt: float
    steps: int
    kn: float = 2e5
    e: float = 0.7
    beta: float = 0.7
    mu: float = 0.5
    dimension: int = 3
    wall: bool = False
    gravity: tuple = None           # (magnitude, x, y, z of its direction)
    coulomb_cutback: bool = False
    settings: str = ""              # more keywords on LIGGGHTS's pair_style line
    extra: str = ""                 # LIGGGHTS commands after the law's properties
    sample_every: int = 0           # print the first particle's velocity every so many steps
    counters: bool = False          # fix contacts/mn on the mobile particles: RESULT counters
    energy: bool = False            # the same with energy yes: RESULT energies too

    def types(self):
        return 2 if any(p.fixed for p in self.particles) else 1


def data_file(scene, atom_types=1):
    """The box and the particles as a data file both engines read (atom_style sphere's and
    granular's Atoms and Velocities sections are the same): the only way to give LIGGGHTS's
    particles a spin, which its `set` command cannot."""
    lo = "0.0" if scene.wall else "-6"
    bounds = [("-60", "60"), ("-60", "60"), ("-0.5", "0.5")] if scene.dimension == 2 else \
        [("-60", "60"), ("-60", "60"), (lo, "60")]
    if scene.dimension == 2:
        bounds[1] = (lo, "60")
    atom_types = max(atom_types, scene.types())
    text = f"particles\n\n{len(scene.particles)} atoms\n{atom_types} atom types\n\n"
    for (a, b), axis in zip(bounds, "xyz"):
        text += f"{a} {b} {axis}lo {axis}hi\n"
    text += "\nAtoms\n\n"
    for n, p in enumerate(scene.particles, start=1):
        text += "{} {} {!r} 1.0 {!r} {!r} {!r}\n".format(n, 2 if p.fixed else 1, p.diameter, *p.x)
    text += "\nVelocities\n\n"
    for n, p in enumerate(scene.particles, start=1):
        text += "{} {!r} {!r} {!r} {!r} {!r} {!r}\n".format(n, *p.v, *p.omega)
    return text


def _masses(scene):
    return "".join(f"set atom {n} mass {p.mass!r}\n"
                   for n, p in enumerate(scene.particles, start=1)) + \
        "group mobile type 1\ngroup base type 2\n"


# fix contacts/mn's global vector with energy yes, by the schema's names (1-based, as f_c[k]):
# both engines' layout
VECTOR = {name: k + 1 for k, name in enumerate(
    (*SCHEMA["counters"], *SCHEMA["vector_extras"], *SCHEMA["energy_sums"]))}
ENERGIES = SCHEMA["energy_sums"]


def _counters(scene):
    if not (scene.counters or scene.energy):
        return ""
    text = "fix c mobile contacts/mn" + (" energy yes\n" if scene.energy else "\n")
    names = []
    for k in range(1, 8):
        text += f"variable c{k} equal f_c[{k}]\n"
        names.append(f"${{c{k}}}")
    text += f'fix result_c all print {scene.steps} "RESULT counters {" ".join(names)}" screen yes\n'
    if scene.energy:
        names = []
        for name in ENERGIES:
            text += f"variable {name} equal f_c[{VECTOR[name]}]\n"
            names.append(f"${{{name}}}")
        text += (f'fix result_e all print {scene.steps} "RESULT energies {" ".join(names)}" '
                 "screen yes\n")
    return text


def _results(scene):
    """Each particle's state printed at the run's last step (by fix print, so that the compute
    is evaluated within the run: neither engine evaluates a per-atom compute between runs)."""
    text = "compute state all property/atom x y z vx vy vz omegax omegay omegaz\n"
    for n in range(1, len(scene.particles) + 1):
        names = []
        for k in range(1, 10):
            text += f"variable s{n}_{k} equal c_state[{n}][{k}]\n"
            names.append(f"${{s{n}_{k}}}")
        text += f'fix result{n} all print {scene.steps} "RESULT state{n} {" ".join(names)}" screen yes\n'
    return text


def _gravity_and_run(scene):
    text = ""
    if scene.gravity:
        text += "fix gravity all gravity {!r} vector {!r} {!r} {!r}\n".format(*scene.gravity)
    if scene.dimension == 2:
        text += "fix flat all enforce2d\n"
    text += f"timestep {scene.dt!r}\n"
    if scene.sample_every:
        spin = 4 if scene.dimension == 2 else 3      # omegaz in 2D, omegay (rolling along x) in 3D
        text += ("compute sample all property/atom vx omegax omegay omegaz\n"
                 "variable t equal step*dt\nvariable vx1 equal c_sample[1][1]\n"
                 f"variable w1 equal c_sample[1][{spin}]\n"
                 f"fix samples all print {scene.sample_every} \"SAMPLE ${{t}} ${{vx1}} ${{w1}}\""
                 " screen yes\n")
    return text + _results(scene) + _counters(scene) + f"run {scene.steps}\n"


def liggghts_deck(scene, wall=None):
    """The scene's LIGGGHTS deck; `wall` replaces the primitive plane wall's commands."""
    walls = "f" if scene.wall else "p"
    boundary = f"p {walls} p" if scene.dimension == 2 else f"p p {walls}"
    plane = "yplane" if scene.dimension == 2 else "zplane"
    pair = "pair_style gran model mn tangential mn"
    n = scene.types()
    table = lambda value: f"{n} " + " ".join([repr(value)] * (n * n))
    if scene.coulomb_cutback:
        pair += " coulomb_cutback on"
    if scene.energy:
        pair += " energy on"
    deck = f"""atom_style granular
atom_modify map array
dimension {scene.dimension}
boundary {boundary}
newton off
communicate single vel yes
units lj
read_data atoms.data
neighbor 0.1 bin
neigh_modify delay 0
fix k all property/global normalStiffnessPerMass peratomtypepair {table(scene.kn)}
fix e all property/global coefficientRestitution peratomtypepair {table(scene.e)}
fix b all property/global coefficientTangentialRestitution peratomtypepair {table(scene.beta)}
fix m all property/global coefficientFriction peratomtypepair {table(scene.mu)}
{scene.extra}{pair} {scene.settings}
pair_coeff * *
"""
    if scene.wall:
        deck += wall or f"fix floor all wall/gran model mn tangential mn primitive type 1 {plane} 0.0\n"
    deck += _masses(scene) + "fix frozen base freeze\nfix integrate mobile nve/sphere\n"
    return deck + _gravity_and_run(scene)


def lammps_deck(scene):
    walls = "f" if scene.wall else "p"
    boundary = f"p {walls} p" if scene.dimension == 2 else f"p p {walls}"
    plane = "yplane" if scene.dimension == 2 else "zplane"
    law = f"kn {scene.kn!r} e {scene.e!r} beta {scene.beta!r} mu {scene.mu!r}"
    if scene.types() == 2:
        law += " wall_types 2"
    if scene.coulomb_cutback:
        law += " coulomb_cutback"
    deck = HEADER.format(plugin=PLUGIN).replace("dimension 2", f"dimension {scene.dimension}")
    deck = deck.replace("boundary p p p", f"boundary {boundary}")
    deck += f"""read_data atoms.data
neigh_modify delay 0
pair_style gran/mn {law}
pair_coeff * *
"""
    if scene.wall:
        deck += f"fix floor all wall/gran/mn {plane} 0.0 NULL\n"
    disc = " disc" if scene.dimension == 2 else ""
    deck += _masses(scene) + f"fix integrate mobile nve/sphere{disc}\n"
    return deck + _gravity_and_run(scene)


@dataclass
class Outcome:
    states: list                    # per particle: x y z vx vy vz wx wy wz
    counters: list = None           # fix contacts/mn's seven sums, where asked for
    energies: dict = None           # its energies' sums by name, where asked for
    samples: list = field(default_factory=list)    # (t, vx, omega) of particle 1
    output: str = ""


def outcome(text, count):
    results = {}
    samples = []
    counters = energies = None
    for line in text.splitlines():
        if line.startswith("RESULT counters "):
            counters = [float(v) for v in line.split()[2:]]
        if line.startswith("RESULT energies "):
            energies = dict(zip(ENERGIES, (float(v) for v in line.split()[2:])))
        m = re.match(r"^RESULT state(\d+) (.*)$", line)
        if m:
            results[int(m.group(1))] = [float(v) for v in m.group(2).split()]
        m = re.match(r"^SAMPLE (\S+) (\S+) (\S+)$", line)
        if m:
            samples.append(tuple(float(v) for v in m.groups()))
    missing = [n for n in range(1, count + 1) if n not in results]
    if missing:
        raise AssertionError(f"no RESULT state for particles {missing}; output tail:\n{text[-3000:]}")
    return Outcome([results[n] for n in range(1, count + 1)], counters, energies, samples, text)


def run_liggghts(deck, workdir, data="", check=True):
    """Runs a LIGGGHTS deck (with its atoms.data, where given) with the project's LIGGGHTS;
    (exit status, output)."""
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    (workdir / "in.liggghts").write_text(deck)
    if data:
        (workdir / "atoms.data").write_text(data)
    proc = subprocess.run([LIGGGHTS, "-in", "in.liggghts", "-echo", "none", "-log",
                           "log.liggghts"], cwd=workdir, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, errors="replace", timeout=1200)
    if check and proc.returncode != 0:
        raise AssertionError(f"liggghts failed ({proc.returncode}):\n{proc.stdout[-4000:]}")
    return proc.returncode, proc.stdout


def run_scene_liggghts(scene, workdir, check=True, wall=None):
    return run_liggghts(liggghts_deck(scene, wall), workdir, data_file(scene), check)


def run_both(scene, workdir):
    """(LIGGGHTS's outcome, lmp's outcome) of the scene."""
    workdir = Path(workdir)
    _, text = run_scene_liggghts(scene, workdir / "liggghts")
    (workdir / "lammps").mkdir(parents=True, exist_ok=True)
    (workdir / "lammps" / "atoms.data").write_text(data_file(scene))
    ours = run_lammps(lammps_deck(scene), workdir / "lammps", header=False)
    return (outcome(text, len(scene.particles)),
            outcome(ours.output, len(scene.particles)))


def run_scene_on_ranks(scene, workdir, ranks):
    """LIGGGHTS's run of `scene` in workdir on `ranks` MPI ranks (its stdout), checked to have
    run on that grid (1 by ranks by 1)."""
    workdir = Path(workdir)
    (workdir / "in.liggghts").write_text(liggghts_deck(scene))
    (workdir / "atoms.data").write_text(data_file(scene))
    proc = subprocess.run([MPIEXEC, "-np", str(ranks), LIGGGHTS, "-in", "in.liggghts",
                           "-echo", "none", "-log", "none"], cwd=workdir, text=True,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=600)
    assert proc.returncode == 0, proc.stdout[-3000:]
    assert f"1 by {ranks} by 1 MPI processor grid" in proc.stdout
    return proc.stdout
