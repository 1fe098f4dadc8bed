"""The scenes of yade_reference.py as LAMMPS 3D decks, and their measurement the same way
(docs/cross_checks_3d.md, "LAMMPS against Yade").

The contact styles are a parameter (`Styles`: the pair style's lines, and the fix that makes
the plane z = 0), so that the same scenes run with pair_style gran/mn + fix wall/gran/mn and with
LAMMPS's own pair_style granular + fix wall/gran granular. Same masses (density 6/pi: a sphere of
diameter 1 has mass 1; the unequal partner has radius 0.3), radii, velocities, spins, gap of 2 tc
before the contact, no gravity, and the same reading: e = -v_n'/v_n and beta = -v_t'.v_t/|v_t|^2
of the contact points from the free flights before and after, tau from the entry and exit times
of those flights (not rounded to dt). Yade's wall and facet are both the plane z = 0 here
(fix ... zplane, the box not periodic in z: fix wall/gran requires it); the facet's record is
the wall's run.

The incline: the plane z = 0 with gravity (g sin theta, 0, -g cos theta), a sphere at rest at its
static overlap; the slopes of v_x and omega_y over the second half of 400 tc."""
import math
from dataclasses import dataclass

import numpy as np

from granmn_run import HEADER, PLUGIN, run_lammps

HEADER_3D = HEADER.format(plugin=PLUGIN).replace("dimension 2", "dimension 3")
SPHERE_DENSITY = 6 / math.pi
THETA = math.radians(20.0)          # yade_reference.THETA
IMPACTS_MEASURED = ("pair_equal", "pair_unequal", "wall")


@dataclass
class Styles:
    """pair: the pair_style and pair_coeff lines (types 1 and 2: radii r1, r2 of a pair; type 1
    alone on a plane); wall: a fix command's text after `fix floor all `, for the plane z = 0."""
    pair: str
    wall: str


def _vec(v):
    return " ".join(repr(float(x)) for x in v)


def _relative(x1, x2, v1, v2, w1, w2, r1, r2):
    n = (x1 - x2) / np.linalg.norm(x1 - x2)
    vc = v1 - v2 + np.cross(n, r1 * w1 + r2 * w2)
    return n, vc


def _tangential(v, n):
    return v - n * (v @ n)


def _entry_exit(x1, x2, v1, v2, t0, R):
    """Times where |d(t)| = R on the free flight d(t) = (x1 - x2) + (v1 - v2)(t - t0)."""
    d, w = x1 - x2, v1 - v2
    a, b, c = w @ w, 2 * d @ w, d @ d - R * R
    s = math.sqrt(b * b - 4 * a * c)
    return t0 + (-b - s) / (2 * a), t0 + (-b + s) / (2 * a)


def _final(run):
    a = run.atoms()
    order = np.argsort(a["id"])
    pick = lambda *names: np.column_stack([a[n][order] for n in names])
    return pick("x", "y", "z"), pick("vx", "vy", "vz"), pick("omegax", "omegay", "omegaz")


DUMP = ("write_dump all custom final.txt id x y z vx vy vz omegax omegay omegaz "
        "modify sort id format float %.17g\n")


def _record(vc_in, n_in, vc_out, n_out, t_in, t_out):
    vt_in, vt_out = _tangential(vc_in, n_in), _tangential(vc_out, n_out)
    rec = {"e": float(-(vc_out @ n_out) / (vc_in @ n_in)), "tau": float(t_out - t_in)}
    if vt_in @ vt_in > 0:
        rec["beta"] = float(-(vt_out @ vt_in) / (vt_in @ vt_in))
        rec["beta_perp"] = float(np.linalg.norm(_tangential(vt_out, vt_in / np.linalg.norm(vt_in)))
                                 / np.linalg.norm(vt_in))
    return rec


def run_3d(workdir, setup, dt, steps):
    """Runs `setup` (box, atoms, styles) in 3D with fix nve/sphere for `steps` steps of dt and
    dumps the final state (DUMP)."""
    deck = f"""{setup}
timestep {dt!r}
fix integrate all nve/sphere
thermo 0
run {steps}
{DUMP}"""
    return run_lammps(HEADER_3D + deck, workdir, header=False)


def approach(V, R, m1, m2, tc):
    """Two bodies (masses m1, m2, contact distance R) 2 tc of flight apart along x, their
    relative velocity V shared so that the total momentum is zero: x1, x2, v1, v2."""
    return np.array([R + 2 * tc, 0.0, 0.0]), np.zeros(3), V * (m2 / (m1 + m2)), -V * (m1 / (m1 + m2))


def two_atoms(x1, x2, r1, r2, v1, v2, w1, w2, masses=None):
    """The LAMMPS lines that make atoms 1 and 2 (types 1 and 2) at x1, x2 with radii r1, r2,
    velocities v1, v2 and spins w1, w2; masses (m1, m2) or, by default, the solid spheres'
    density."""
    mass = (f"set atom 1 mass {masses[0]!r}\nset atom 2 mass {masses[1]!r}" if masses else
            f"set group all density {SPHERE_DENSITY!r}")
    return f"""create_atoms 1 single {_vec(x1)}
create_atoms 2 single {_vec(x2)}
set atom 1 diameter {2 * r1!r}
set atom 2 diameter {2 * r2!r}
{mass}
velocity all set 0 0 0
set atom 1 vx {v1[0]!r} vy {v1[1]!r} vz {v1[2]!r} omega {_vec(w1)}
set atom 2 vx {v2[0]!r} vy {v2[1]!r} vz {v2[2]!r} omega {_vec(w2)}"""


def pair_impact(run, x1, x2, v1, v2, w1, w2, r1, r2, T):
    """e, beta, tau of the impact of atoms 1 and 2 started at x1, x2, v1, v2, w1, w2, from the
    run's final state at time T (entry and exit from the free flights before and after)."""
    x, v, w = _final(run)
    R = r1 + r2
    t_in, _ = _entry_exit(x1, x2, v1, v2, 0.0, R)
    _, t_out = _entry_exit(x[0], x[1], v[0], v[1], T, R)
    n_in, vc_in = _relative(x1 + v1 * t_in, x2 + v2 * t_in, v1, v2, w1, w2, r1, r2)
    n_out, vc_out = _relative(x[0] + v[0] * (t_out - T), x[1] + v[1] * (t_out - T),
                              v[0], v[1], w[0], w[1], r1, r2)
    rec = _record(vc_in, n_in, vc_out, n_out, t_in, t_out)
    rec["output"] = run.output
    return rec, v


def pair(styles, workdir, tc, dt, r1=0.5, r2=0.5, oblique=True):
    """yade_reference.pair: c_1 - c_2 = (-1, 0.4, -0.25) (approach speed 1 along x), spins
    (3, 5, -12) 0.5/r1 and (-7, 2, 9) 0.5/r2; oblique=False: head-on, no spin (a normal impact)."""
    m1, m2 = (2 * r1) ** 3, (2 * r2) ** 3
    V = np.array([-1.0, 0.4, -0.25]) if oblique else np.array([-1.0, 0.0, 0.0])
    w1 = np.array([3.0, 5.0, -12.0]) * (0.5 / r1) if oblique else np.zeros(3)
    w2 = np.array([-7.0, 2.0, 9.0]) * (0.5 / r2) if oblique else np.zeros(3)
    x1, x2, v1, v2 = approach(V, r1 + r2, m1, m2, tc)
    steps = int(round(5 * tc / dt))
    setup = f"""
region box block -5 5 -5 5 -5 5
create_box 2 box
{two_atoms(x1, x2, r1, r2, v1, v2, w1, w2)}
{styles.pair}
"""
    run = run_3d(workdir, setup, dt, steps)
    rec, v = pair_impact(run, x1, x2, v1, v2, w1, w2, r1, r2, steps * dt)
    rec["momentum_error"] = float(np.linalg.norm(m1 * v[0] + m2 * v[1] - (m1 * v1 + m2 * v2)))
    return rec


def sphere_above_plane(z0):
    """The LAMMPS lines of a box open at z = 0 (the plane) with one sphere of diameter 1 at rest
    at (0, 0, z0)."""
    return f"""boundary p p f
region box block -5 5 -5 5 -5 5
create_box 2 box
create_atoms 1 single 0 0 {z0!r}
set group all diameter 1.0
set group all density {SPHERE_DENSITY!r}
velocity all set 0 0 0"""


def plane(styles, workdir, tc, dt, oblique=True):
    """yade_reference.plane: a sphere of diameter 1 at (0, 0, r + 2 tc), velocity
    (0.4, -0.25, -1), spin (3, 5, -12), onto z = 0."""
    r = 0.5
    c = np.array([0.4, -0.25, -1.0]) if oblique else np.array([0.0, 0.0, -1.0])
    w0 = np.array([3.0, 5.0, -12.0]) if oblique else np.zeros(3)
    z0 = r + 2 * tc
    steps = int(round(6 * tc / dt))
    setup = f"""
{sphere_above_plane(z0)}
set atom 1 vx {c[0]!r} vy {c[1]!r} vz {c[2]!r} omega {_vec(w0)}
{styles.pair}
fix floor all {styles.wall}
"""
    run = run_3d(workdir, setup, dt, steps)
    x, v, w = _final(run)
    T = steps * dt
    n = np.array([0.0, 0.0, 1.0])
    t_in = 2 * tc / -c[2]
    t_out = T - (x[0, 2] - r) / v[0, 2]
    rec = _record(c + np.cross(n, r * w0), n, v[0] + np.cross(n, r * w[0]), n, t_in, t_out)
    rec["output"] = run.output
    return rec


def _slope(ts, ys):
    ts, ys = np.asarray(ts), np.asarray(ys)
    return float(np.polyfit(ts, ys, 1)[0])


def incline(styles, workdir, tc, dt, k_per_mass, mu, samples=40):
    """yade_reference.rolling: the sphere at rest at its static overlap g cos(theta)/k on the
    plane z = 0 (k: the plane's normal stiffness per unit of the sphere's mass), gravity tilted
    by THETA; v_x and omega_y every 1/samples of 400 tc, fitted over the second half."""
    r, g = 0.5, 1.0
    steps = int(round(400 * tc / dt))
    per = steps // samples
    z0 = r - g * math.cos(THETA) / k_per_mass
    deck = f"""
{sphere_above_plane(z0)}
{styles.pair}
fix floor all {styles.wall}
fix gravity all gravity {g!r} vector {math.sin(THETA)!r} 0 {-math.cos(THETA)!r}
timestep {dt!r}
fix integrate all nve/sphere
variable t equal time
variable vx equal vx[1]
compute spin all property/atom omegay
compute wy all reduce sum c_spin
variable wy equal c_wy
fix trace all print {per} "${{t}} ${{vx}} ${{wy}}" file trace.txt screen no
thermo 0
run {per * samples}
"""
    run = run_lammps(HEADER_3D + deck, workdir, header=False)
    t, vx, wy = run.table("trace.txt")[1:].T          # the first row is step 0
    half = len(t) // 2
    return {"theta": THETA, "mu": mu, "g": g, "r": r,
            "acceleration": _slope(t[half:], vx[half:]),
            "angular_acceleration": _slope(t[half:], wy[half:]),
            "max_slip_speed": float(np.max(np.abs(vx[half:] - r * wy[half:])))}


def discs(styles, workdir, tc, dt, r1=0.5, r2=0.3, m1=1.0, m2=0.36):
    """The 2D analogue of `pair` (no Yade scene): discs (fix nve/sphere disc, I = m r^2/2) of
    radii r1, r2 and masses m1, m2 set directly, c_1 - c_2 = (-1, 0.4) (approach speed 1 along
    x), spins 12 (0.5/r1) and -7 (0.5/r2) about z."""
    V = np.array([-1.0, 0.4, 0.0])
    w1, w2 = np.array([0.0, 0.0, 12.0 * 0.5 / r1]), np.array([0.0, 0.0, -7.0 * 0.5 / r2])
    x1, x2, v1, v2 = approach(V, r1 + r2, m1, m2, tc)
    steps = int(round(5 * tc / dt))
    deck = f"""
region box block -5 5 -5 5 -0.5 0.5
create_box 2 box
{two_atoms(x1, x2, r1, r2, v1, v2, w1, w2, masses=(m1, m2))}
{styles.pair}
timestep {dt!r}
fix integrate all nve/sphere disc
fix flat all enforce2d
thermo 0
run {steps}
{DUMP}"""
    run = run_lammps(deck, workdir)          # granmn_run's 2D header
    return pair_impact(run, x1, x2, v1, v2, w1, w2, r1, r2, steps * dt)[0]


def impacts(styles_pair_equal, styles_pair_unequal, styles_plane, workdir, tc, dt):
    """The hook's `other` record for the impacts: pair_equal, pair_unequal, wall, and the facet
    as the wall's run."""
    out = {"pair_equal": pair(styles_pair_equal, workdir / "pair_equal", tc, dt, 0.5, 0.5),
           "pair_unequal": pair(styles_pair_unequal, workdir / "pair_unequal", tc, dt, 0.5, 0.3),
           "wall": plane(styles_plane, workdir / "wall", tc, dt)}
    out["facet"] = out["wall"]
    return out


if __name__ == "__main__":
    # The dt dependence quoted in docs/cross_checks_3d.md: gran/mn's errors against this law's
    # predictions at several steps per tc, in units of dt/tc. Run from the repository root with
    # GRANMN_LMP and GRANMN_PLUGIN set and the test suite's path (pytest.ini's pythonpath):
    #     PYTHONPATH=.:tests/lammps python3 -m yade_lammps_scenes WORKDIR [STEPS_PER_TC ...]
    import json
    import sys
    from pathlib import Path

    import yade_cross_check as yc

    work = Path(sys.argv[1])
    steps = [float(s) for s in sys.argv[2:]] or [50.0, 100.0, 200.0, 400.0]
    numbers = json.loads(yc.NUMBERS.read_text())
    for case, ref in numbers.items():
        pred = yc.predictions(ref)
        law = yc.mn_sphere_law(ref["tc"], ref["en"], ref["et"])
        for extra, key in (("", "mn"), ("limit_damping", "yade")):
            styles = Styles(f"pair_style gran/mn kn {law['kn']!r} e {ref['en']!r} beta "
                            f"{ref['et']!r} mu 1e6 {extra}\npair_coeff * *",
                            "wall/gran/mn zplane 0.0 NULL")
            for n in steps:
                tc = ref["tc"]
                got = impacts(styles, styles, styles, work / f"{case}_{key}_{n:g}", tc, tc / n)
                row = []
                for name in IMPACTS_MEASURED:
                    p = pred[name][key]
                    row += [f"{(got[name][q] - p[q]) / (tc if q == 'tau' else 1.0) * n:+.3f}"
                            for q in ("e", "beta", "tau")]
                print(case, extra or "plain", f"{n:g} steps/tc", "err/(dt/tc) e beta tau for",
                      " / ".join(IMPACTS_MEASURED), ":", " ".join(row), flush=True)
