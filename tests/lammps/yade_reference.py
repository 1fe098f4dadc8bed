# Run by Yade's own interpreter, not by python3:
#     yade -n -x tests/lammps/yade_reference.py OUT.json [TC EN ET STEPS_PER_TC]
# (-n: no GUI, -x: exit when the script ends.) Yade 2023.02 (Debian's `yade`).
#
# The independent reference for the 3D law: ViscElMat with (tc, en, et),
# Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator without
# numerical damping, dt = tc / STEPS_PER_TC. It measures and writes as JSON:
#   pair_equal, pair_unequal: an oblique, spinning impact of two solid spheres (no gravity);
#   wall: a sphere hitting a fixed plane (a Wall body: mass 0) obliquely, spinning;
#   facet: the same against a large Facet (mass 0);
#   rolling: a sphere resting on a plane under gravity tilted by theta (the plane inclined),
#            friction large enough to roll without slip (mu = 0.5): its centre's acceleration;
#   sliding: the same with mu = 0.05 < (2/7) tan(theta): it slides from the start;
# each impact with e = -v_n'/v_n, beta = -v_t'.v_t/|v_t|^2 (v_t: the tangential velocity of the
# contact points), the duration of the geometric overlap (entry and exit times from the free
# flights before and after, so not rounded to dt) and the force-carrying duration (steps with a
# positive normal force, times dt). It also records the contact's kn, cn, ks, cs as Yade built
# them, so that the mapping can be checked against docs/cross_checks_3d.md.
# Units: sphere diameter 1, mass 1 (r = 0.5), g = 1 in the rolling scene.
import json
import math
import sys

import yade.config
from yade import O, utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb, Bo1_Wall_Aabb,
                          Bo1_Facet_Aabb, InteractionLoop, Ig2_Sphere_Sphere_ScGeom,
                          Ig2_Wall_Sphere_ScGeom, Ig2_Facet_Sphere_ScGeom,
                          Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_ViscElPhys_Basic,
                          NewtonIntegrator, ViscElMat)
from yade.minieigenHP import Vector3

args = sys.argv[1:]
OUT = args[0] if args else "yade_reference.json"
TC = float(args[1]) if len(args) > 1 else 1e-4
EN = float(args[2]) if len(args) > 2 else 0.7
ET = float(args[3]) if len(args) > 3 else 0.7
STEPS_PER_TC = float(args[4]) if len(args) > 4 else 200.0
THETA = math.radians(20.0)
RHO = 6.0 / math.pi          # r = 0.5 -> m = 1


def reset(gravity, mu):
    O.reset()
    mat = O.materials.append(ViscElMat(tc=TC, en=EN, et=ET, density=RHO,
                                       frictionAngle=math.atan(mu)))
    O.engines = [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb(), Bo1_Facet_Aabb()]),
        InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom(),
                         Ig2_Facet_Sphere_ScGeom()],
                        [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                        [Law2_ScGeom_ViscElPhys_Basic()]),
        NewtonIntegrator(damping=0.0, gravity=gravity),
    ]
    O.dt = TC / STEPS_PER_TC
    return mat


def vec(v):
    return [float(v[0]), float(v[1]), float(v[2])]


def tangential(v, n):
    return v - n * v.dot(n)


def phys_record(i):
    p = i.phys
    return {"kn": p.kn, "cn": p.cn, "ks": p.ks, "cs": p.cs}


def run_contact(id1, id2, gap_of):
    """Step until the contact (id1, id2) has come and gone; return the force-carrying steps and
    the contact's parameters. gap_of(): the current geometric gap (negative: overlap)."""
    force_steps, params, seen, after = 0, None, False, 0
    limit = int(60 * STEPS_PER_TC)                 # the contact starts after 2 tc
    for _ in range(limit):
        O.step()
        i = O.interactions[id1, id2] if O.interactions.has(id1, id2) else None
        if i is not None and i.isReal:
            if params is None:
                params = phys_record(i)
            if i.phys.normalForce.norm() > 0:
                force_steps += 1
        if gap_of() < 0:
            seen = True
        elif seen:
            after += 1
            if after > 20:
                break
    assert seen and params is not None, "no contact happened"
    return force_steps, params


def entry_exit_pair(x1, x2, v1, v2, t0, R):
    """Times where |d(t)| = R on the free flight d(t) = (x1-x2) + (v1-v2)(t-t0): the first root
    (entry) and the last (exit)."""
    d, w = x1 - x2, v1 - v2
    a, b, c = w.dot(w), 2 * d.dot(w), d.dot(d) - R * R
    s = math.sqrt(b * b - 4 * a * c)
    return t0 + (-b - s) / (2 * a), t0 + (-b + s) / (2 * a)


def pair(r1, r2):
    reset(Vector3(0, 0, 0), 1e8)
    a = O.bodies.append(utils.sphere(Vector3(0, 0, 0), r1))
    b = O.bodies.append(utils.sphere(Vector3(0, 0, 0), r2))
    A, B = O.bodies[a].state, O.bodies[b].state
    m1, m2 = A.mass, B.mass
    R = r1 + r2
    V = Vector3(-1.0, 0.4, -0.25)                  # c_1 - c_2: approach 1, oblique in 3D
    w1, w2 = Vector3(3.0, 5.0, -12.0) * (0.5 / r1), Vector3(-7.0, 2.0, 9.0) * (0.5 / r2)
    gap = 2 * TC                                   # 2 tc of free flight before the contact
    A.pos, B.pos = Vector3(R + gap, 0, 0), Vector3(0, 0, 0)
    A.vel, B.vel = V * (m2 / (m1 + m2)), -V * (m1 / (m1 + m2))
    A.angVel, B.angVel = w1, w2
    x1, x2, c1, c2 = Vector3(A.pos), Vector3(B.pos), Vector3(A.vel), Vector3(B.vel)
    t_in, _ = entry_exit_pair(x1, x2, c1, c2, 0.0, R)
    n_in = (x1 - x2 + (c1 - c2) * t_in).normalized()

    def gap_of():
        return (A.pos - B.pos).norm() - R

    force_steps, params = run_contact(a, b, gap_of)
    T = O.time
    X1, X2, C1, C2 = Vector3(A.pos), Vector3(B.pos), Vector3(A.vel), Vector3(B.vel)
    W1, W2 = Vector3(A.angVel), Vector3(B.angVel)
    _, t_out = entry_exit_pair(X1, X2, C1, C2, T, R)
    n_out = (X1 - X2 + (C1 - C2) * (t_out - T)).normalized()
    vc_in = (c1 - c2) + n_in.cross(w1 * r1 + w2 * r2)
    vc_out = (C1 - C2) + n_out.cross(W1 * r1 + W2 * r2)
    vt_in, vt_out = tangential(vc_in, n_in), tangential(vc_out, n_out)
    return {
        "r1": r1, "r2": r2, "m1": m1, "m2": m2, "I1": A.inertia[0], "I2": B.inertia[0],
        "e": -vc_out.dot(n_out) / vc_in.dot(n_in),
        "beta": -vt_out.dot(vt_in) / vt_in.dot(vt_in),
        "beta_perp": tangential(vt_out, vt_in.normalized()).norm() / vt_in.norm(),
        "tau": t_out - t_in, "tau_force": force_steps * O.dt,
        "vt_in": vec(vt_in), "vt_out": vec(vt_out), "params": params,
    }


def plane(kind):
    reset(Vector3(0, 0, 0), 1e8)
    r = 0.5
    if kind == "wall":
        w = O.bodies.append(utils.wall(0.0, axis=2))
    else:
        L = 50.0
        w = O.bodies.append(utils.facet([Vector3(-L, -L, 0), Vector3(L, -L, 0),
                                         Vector3(0, L, 0)], wire=False))
    s = O.bodies.append(utils.sphere(Vector3(0, 0, 0), r))
    S = O.bodies[s].state
    gap = 2 * TC
    c, w0 = Vector3(0.4, -0.25, -1.0), Vector3(3.0, 5.0, -12.0)
    S.pos, S.vel, S.angVel = Vector3(0, 0, r + gap), c, w0
    n = Vector3(0, 0, 1)                           # from the plane to the sphere
    t_in = gap / -c[2]

    def gap_of():
        return S.pos[2] - r

    force_steps, params = run_contact(w, s, gap_of)
    T, X, C, W = O.time, Vector3(S.pos), Vector3(S.vel), Vector3(S.angVel)
    t_out = T - (X[2] - r) / C[2]
    vc_in, vc_out = c + n.cross(w0 * r), C + n.cross(W * r)
    vt_in, vt_out = tangential(vc_in, n), tangential(vc_out, n)
    return {
        "m": S.mass, "I": S.inertia[0], "r": r, "boundary_mass": O.bodies[w].state.mass,
        "e": -vc_out.dot(n) / vc_in.dot(n),
        "beta": -vt_out.dot(vt_in) / vt_in.dot(vt_in),
        "beta_perp": tangential(vt_out, vt_in.normalized()).norm() / vt_in.norm(),
        "tau": t_out - t_in, "tau_force": force_steps * O.dt,
        "vt_in": vec(vt_in), "vt_out": vec(vt_out), "params": params,
    }


def slope(ts, ys):
    """Least-squares slope of ys(ts)."""
    tm, ym = sum(ts) / len(ts), sum(ys) / len(ys)
    return (sum((a - tm) * (b - ym) for a, b in zip(ts, ys))
            / sum((a - tm) ** 2 for a in ts))


def rolling(mu=0.5, samples=40):
    """The plane z = 0 inclined by THETA: gravity (g sin, 0, -g cos). The sphere starts at rest
    at its static overlap (no bounce); the slopes of v_x and of the spin omega_y over the second
    half of the run are its accelerations. It rolls without slip while mu > (2/7) tan(theta),
    and slides (the contact at the Coulomb limit throughout) below. 400 tc: the tangential
    oscillation of the start has decayed by exp(-400 |ln et| / 2) long before the fit."""
    duration = 400 * TC
    g = 1.0
    reset(Vector3(g * math.sin(THETA), 0, -g * math.cos(THETA)), mu)
    r = 0.5
    w = O.bodies.append(utils.wall(0.0, axis=2))
    s = O.bodies.append(utils.sphere(Vector3(0, 0, r), r))
    S = O.bodies[s].state
    kn = (S.mass / 2) * (math.pi ** 2 + math.log(EN) ** 2) / TC ** 2   # Yade's kn, see docs
    S.pos = Vector3(0, 0, r - S.mass * g * math.cos(THETA) / kn)
    steps = int(round(duration / O.dt))
    per = steps // samples
    ts, vs, ws, slips = [], [], [], []
    for _ in range(samples):
        O.run(per, True)
        ts.append(O.time)
        vs.append(S.vel[0])
        ws.append(S.angVel[1])
        slips.append(S.vel[0] - r * S.angVel[1])   # contact-point velocity (x) on the plane
    half = samples // 2
    return {"theta": THETA, "mu": mu, "g": g, "r": r, "time": ts[-1], "v_end": vs[-1],
            "acceleration": slope(ts[half:], vs[half:]),
            "angular_acceleration": slope(ts[half:], ws[half:]),
            "max_slip_speed": max(abs(x) for x in slips[half:]),
            "in_contact": O.interactions.has(w, s) and O.interactions[w, s].isReal}


result = {"yade_version": yade.config.version,
          "tc": TC, "en": EN, "et": ET, "steps_per_tc": STEPS_PER_TC, "dt": TC / STEPS_PER_TC,
          "pair_equal": pair(0.5, 0.5), "pair_unequal": pair(0.5, 0.3),
          "wall": plane("wall"), "facet": plane("facet"), "rolling": rolling(0.5),
          "sliding": rolling(0.05)}
with open(OUT, "w") as f:
    json.dump(result, f, indent=1)
print("yade_reference: wrote", OUT)
