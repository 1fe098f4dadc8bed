"""Analytic predictions for the Yade cross-check of the 3D law (docs/cross_checks_3d.md) and the
hook that compares another engine's 3D numbers with the same Yade reference.

Two laws, both linear spring-dashpots on a sticking contact, read the docs' way (the normal
and tangential modes decoupled, the normal's turning neglected):
- this project's law with the sphere mapping (docs/model.md section 3.1, q = 7/2), whose
  normal force may turn attractive at the end of a contact: it gives (e, beta, tau_c) exactly
  for two spheres and (e_w, beta_w, tau_w) against a plane;
- Yade's ViscElMat (tc, en, et) as Yade 2023.02 builds it (`yade_parameters`), whose
  Law2_ScGeom_ViscElPhys_Basic sets a negative normal force to zero (and, with it, the tangential
  force: the Coulomb cap is then 0), so a contact stops carrying force at t* < the end of the
  overlap.
No LAMMPS here: `compare_engine` takes the measured numbers of any engine."""
import json
import math
import shutil
import subprocess
from pathlib import Path

from granmn_run import law as header_law

HERE = Path(__file__).resolve().parent
SCRIPT = HERE / "yade_reference.py"
SOLID_SPHERE_Q = 3.5          # q = 1 + m r^2 / I, I = 2 m r^2 / 5
DISC_Q = 3.0                  # I = m r^2 / 2: the 2D mapping
IMPACTS = ("pair_equal", "pair_unequal", "wall", "facet")
# The reference runs (test_yade.py; their numbers committed in NUMBERS for the hook):
# (en, et) equal (beta_w = e_w on a plane), and strongly damped with et != en.
CASES = {"e0.7_b0.7": (0.7, 0.7), "e0.5_b0.3": (0.5, 0.3)}
TC, STEPS_PER_TC = 1e-4, 200.0
NUMBERS = HERE / "yade_reference_numbers.json"


# ---------------------------------------------------------------- Yade's mapping (the source)
def yade_parameters(tc, en, et, m1, m2):
    """kn, cn, ks, cs of Ip2_ViscElMat_ViscElMat_ViscElPhys for masses m1, m2 (0: a wall or a
    facet, replaced by the other body's mass), as docs/cross_checks_3d.md quotes the source."""
    if m1 == 0.0:
        m1 = m2
    if m2 == 0.0:
        m2 = m1
    mr = m1 * m2 / (m1 + m2)
    ln_en, ln_et = math.log(en), math.log(et)
    return {"kn": mr * (math.pi ** 2 + ln_en ** 2) / tc ** 2,
            "cn": -2.0 * mr * ln_en / tc,
            "ks": 2.0 / 7.0 * mr * (math.pi ** 2 + ln_et ** 2) / tc ** 2,
            "cs": -4.0 / 7.0 * mr * ln_et / tc}


def effective_masses(m1, I1, r1, m2=None, I2=None, r2=None):
    """Normal and tangential effective masses of a contact: 1/m_n = 1/m1 + 1/m2,
    1/m_t = 1/m1 + 1/m2 + r1^2/I1 + r2^2/I2; m2 None: a fixed plane (infinite mass)."""
    inv_n = 1.0 / m1 + (0.0 if m2 is None else 1.0 / m2)
    inv_t = inv_n + r1 ** 2 / I1 + (0.0 if m2 is None else r2 ** 2 / I2)
    return 1.0 / inv_n, 1.0 / inv_t


# ------------------------------------------------------------------ the sticking-contact analysis
def _mode(k_per_mass, c_per_mass):
    """u'' + 2 gamma u' + w0^2 u = 0: (gamma, w) with w^2 = w0^2 - gamma^2 (underdamped)."""
    gamma = 0.5 * c_per_mass
    w2 = k_per_mass - gamma ** 2
    if w2 <= 0.0:
        raise ValueError("overdamped mode: no restitution to predict")
    return gamma, math.sqrt(w2)


def _velocity(gamma, w, t):
    """u'(t)/u'(0) of the mode started at u = 0."""
    return math.exp(-gamma * t) * (math.cos(w * t) - gamma / w * math.sin(w * t))


def predict(kn, cn, ks, cs, m_n, m_t, clamp):
    """e, beta, tau (the overlap's duration) and tau_force (the time the normal force is
    positive) of a sticking contact. clamp: the normal force k delta + c delta' is set to 0
    where negative (Yade); the overlap then ends in free flight and the tangential force, capped
    by mu * 0, vanishes with it. Without clamp (this project's law) the force turns attractive
    and everything ends at half the normal period."""
    g, w = _mode(kn / m_n, cn / m_n)
    gt, wt = _mode(ks / m_t, cs / m_t)
    if not clamp:
        t_end = math.pi / w
        return {"e": math.exp(-g * t_end), "beta": -_velocity(gt, wt, t_end),
                "tau": t_end, "tau_force": t_end}
    # F/(m_n v0 e^{-g t}) = (w^2 - g^2)/w sin(wt) + 2 g cos(wt): zero at t*.
    t_star = (math.pi - math.atan2(2.0 * g * w, w * w - g * g)) / w
    depth = math.exp(-g * t_star) * math.sin(w * t_star) / w       # delta(t*)/v0
    speed = -_velocity(g, w, t_star)                                 # -delta'(t*)/v0
    return {"e": speed, "beta": -_velocity(gt, wt, t_star),
            "tau": t_star + depth / speed, "tau_force": t_star}


def mn_sphere_law(tau_c, e, beta, q=SOLID_SPHERE_Q):
    """This project's coefficients (docs/model.md sections 3 and 3.1), as the header derives them
    (mn-law), for the k_n that gives tau_c: k_n, eta_n, k_t, eta_t per unit of 2M (or of m_i
    against the boundary). q: SOLID_SPHERE_Q, or DISC_Q for the disc mapping on spheres (the
    mutation the checks must see)."""
    shape = {SOLID_SPHERE_Q: "sphere", DISC_Q: "disc"}[q]
    ln_e = math.log(e)
    kn = (math.pi ** 2 + ln_e ** 2) / (2.0 * tau_c ** 2)    # tau_c's definition, inverted
    derived = header_law(kn, e, beta, shape)
    return {"kn": kn, "eta_n": derived["eta_n"], "kt": derived["kt"], "eta_t": derived["eta_t"]}


def mn_forces(law, m1, m2):
    """The law's absolute kn, cn, ks, cs for masses m1, m2 (m2 None: the boundary, 2M -> m1)."""
    two_m = m1 if m2 is None else 2.0 * m1 * m2 / (m1 + m2)
    return {"kn": two_m * law["kn"], "cn": two_m * law["eta_n"],
            "ks": two_m * law["kt"], "cs": two_m * law["eta_t"]}


def scene_masses(scene):
    """(m_n, m_t) of a measured impact record of yade_reference.py."""
    if "m1" in scene:
        return effective_masses(scene["m1"], scene["I1"], scene["r1"],
                                scene["m2"], scene["I2"], scene["r2"])
    return effective_masses(scene["m"], scene["I"], scene["r"])


def predictions(ref):
    """{impact: {'yade': law with clamp, 'mn': this project's law}} for a reference's scenes,
    both from the formulas (not from the numbers Yade printed)."""
    out = {}
    law = mn_sphere_law(ref["tc"], ref["en"], ref["et"])
    for name in IMPACTS:
        s = ref[name]
        m_n, m_t = scene_masses(s)
        if "m1" in s:
            yade = yade_parameters(ref["tc"], ref["en"], ref["et"], s["m1"], s["m2"])
            mn = mn_forces(law, s["m1"], s["m2"])
        else:
            yade = yade_parameters(ref["tc"], ref["en"], ref["et"], s["m"], s["boundary_mass"])
            mn = mn_forces(law, s["m"], None)
        out[name] = {"yade": predict(**yade, m_n=m_n, m_t=m_t, clamp=True),
                     "mn": predict(**mn, m_n=m_n, m_t=m_t, clamp=False),
                     "yade_parameters": yade, "mn_parameters": mn}
    return out


def rolling_acceleration(theta, g=1.0, q=SOLID_SPHERE_Q):
    """A sphere rolling without slip down a plane: a = g sin(theta) / (1 + I/(m r^2))
    = g sin(theta) (q - 1)/q, 5/7 g sin(theta) for a solid sphere."""
    return g * math.sin(theta) * (q - 1.0) / q


def incline(theta, mu, g=1.0, r=0.5, q=SOLID_SPHERE_Q):
    """A sphere released at rest on a plane inclined by theta: it rolls without slip at
    rolling_acceleration if mu >= tan(theta)/q, the friction needed being g sin(theta)/q; else it
    slides with friction mu m g cos(theta) against the motion: a = g (sin - mu cos), and the
    spin at mu m g cos(theta) r / I = mu g cos(theta) (q - 1)/r."""
    if mu * q >= math.tan(theta):
        a = rolling_acceleration(theta, g, q)
        return {"rolls": True, "acceleration": a, "angular_acceleration": a / r}
    return {"rolls": False, "acceleration": g * (math.sin(theta) - mu * math.cos(theta)),
            "angular_acceleration": mu * g * math.cos(theta) * (q - 1.0) / r}


def incline_problems(measured, who="", rtol=None):
    """Problems of a measured incline record ('rolling' or 'sliding' of yade_reference.py)."""
    rtol = ROLLING_RTOL if rtol is None else rtol
    p = incline(measured["theta"], measured["mu"], measured.get("g", 1.0),
                measured.get("r", 0.5))
    problems = []
    for k in ("acceleration", "angular_acceleration"):
        if k in measured and not abs(measured[k] - p[k]) <= rtol * abs(p[k]):
            problems.append(f"{who} mu {measured['mu']}: {k} {measured[k]:.8g}, predicted "
                            f"{p[k]:.8g} ({'rolling' if p['rolls'] else 'sliding'})")
    return problems


# ------------------------------------------------------------------------------------ tolerances
def tolerance(steps_per_tc, quantity):
    """Yade's NewtonIntegrator is leapfrog: the force at step n sees the velocity of half a step
    earlier, so the dashpots act with a lag of dt/2 and the contact starts and ends inside a
    step. Both errors are first order in dt/tc: measured at 50 ... 800 steps per tc, the error
    of e, beta and tau is at most 0.3 dt/tc, of tau_force (whole steps) 0.9 dt/tc
    (docs/cross_checks_3d.md). The tolerance is 1 dt/tc (over 3x that), tau_force 3 dt/tc.
    At the default 200 steps per tc: 0.005 on e and beta, 0.005 tc on tau."""
    base = 1.0 / steps_per_tc
    return base + (2.0 / steps_per_tc if quantity == "tau_force" else 0.0)


# --------------------------------------------------------------------------------- running Yade
def yade_executable():
    return shutil.which("yade")


def run_reference(workdir, tc=1e-4, en=0.7, et=0.7, steps_per_tc=200.0):
    """Run yade_reference.py with Yade (headless) and return its JSON."""
    exe = yade_executable()
    if exe is None:
        raise FileNotFoundError("yade is not installed (scripts/setup.sh installs it)")
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    out = workdir / "yade_reference.json"
    cmd = [exe, "-n", "-x", str(SCRIPT), str(out), repr(tc), repr(en), repr(et),
           repr(steps_per_tc)]
    proc = subprocess.run(cmd, cwd=workdir, capture_output=True, text=True, errors="replace",
                          timeout=600)
    if proc.returncode != 0 or not out.exists():
        raise RuntimeError(f"{' '.join(cmd)} failed ({proc.returncode}):\n"
                           + proc.stdout[-2000:] + proc.stderr[-2000:])
    return json.loads(out.read_text())


# ------------------------------------------------------------------- the hook for other engines
def check_impact(measured, predicted, steps_per_tc, tau_unit):
    """Problems (strings) where measured e, beta, tau differ from predicted beyond the tolerance
    at steps_per_tc; tau in units of tau_unit (the requested tc)."""
    problems = []
    for q in ("e", "beta", "tau"):
        if q not in measured:
            continue
        scale = tau_unit if q == "tau" else 1.0
        err = abs(measured[q] - predicted[q]) / scale
        tol = tolerance(steps_per_tc, q)
        if not err <= tol:
            problems.append(f"{q}: measured {measured[q]:.6g}, predicted {predicted[q]:.6g} "
                            f"(|diff| {err:.3g}{' tc' if q == 'tau' else ''} > {tol:.3g})")
    return problems


def compare_engine(other, ref, other_steps_per_tc, clamp=False):
    """THE HOOK for the LAMMPS 3D side (not implemented here). `other` is
    {impact: {'e': .., 'beta': .., 'tau': ..}, 'rolling': {..}, 'sliding': {..}}
    measured by another engine with the same (tc, en, et) = (tau_c, e, beta) as the Yade
    reference `ref` (run_reference's JSON), impacts named as in IMPACTS and set up as in
    yade_reference.py (the facet is a plane like the wall). It returns a list of problems
    (empty: agreement):
    - each impact against this project's law's prediction (clamp=False: attractive end, e, beta,
      tau_c exact for a pair) or Yade's (clamp=True: for an engine that clamps like Yade), at the
      other engine's own time step;
    - Yade's measured number against Yade's prediction at Yade's time step, so that the Yade
      side of the comparison is itself checked;
    - the difference other - Yade against the predicted difference (the clamp's effect, 0 when
      clamp=True), within the sum of both tolerances;
    - on the incline ('rolling', mu = 0.5, and 'sliding', mu = 0.05: {theta, mu, g, r,
      acceleration, angular_acceleration}) both against `incline`: rolling at 5/7 g sin(theta),
      sliding at g (sin - mu cos)."""
    problems = []
    pred = predictions(ref)
    for name in IMPACTS:
        if name not in other:
            continue
        p_other = pred[name]["yade" if clamp else "mn"]
        p_yade = pred[name]["yade"]
        for msg in check_impact(other[name], p_other, other_steps_per_tc, ref["tc"]):
            problems.append(f"{name} (other engine): {msg}")
        for msg in check_impact(ref[name], p_yade, ref["steps_per_tc"], ref["tc"]):
            problems.append(f"{name} (Yade): {msg}")
        for q in ("e", "beta", "tau"):
            if q not in other[name]:
                continue
            scale = ref["tc"] if q == "tau" else 1.0
            diff = (other[name][q] - ref[name][q]) / scale
            expect = (p_other[q] - p_yade[q]) / scale
            tol = tolerance(other_steps_per_tc, q) + tolerance(ref["steps_per_tc"], q)
            if not abs(diff - expect) <= tol:
                problems.append(f"{name}: {q} other - Yade = {diff:.4g}, predicted "
                                f"{expect:.4g} (tolerance {tol:.3g})")
    for scene in ("rolling", "sliding"):
        if scene in other:
            problems += incline_problems(other[scene], f"{scene} (other engine)")
            problems += incline_problems(ref[scene], f"{scene} (Yade)")
    return problems


# The incline's accelerations are fitted over 200..400 tc of steady rolling or sliding, where the
# integration error of a constant-force motion is nil and the only deviation is the damped
# tangential oscillation of the start (its velocity amplitude ~ (2/7) g sin(theta) tc / pi):
# 1e-4 relative is ample (measured: 2e-9), and a disc's 2/3 (or sliding for rolling) is far
# outside it.
ROLLING_RTOL = 1e-4


if __name__ == "__main__":
    # Rewrites NUMBERS from Yade: /usr/bin/python3 tests/lammps/yade_cross_check.py WORKDIR
    import sys
    work = Path(sys.argv[1] if len(sys.argv) > 1 else "yade_work")
    numbers = {name: run_reference(work / name, TC, en, et, STEPS_PER_TC)
               for name, (en, et) in CASES.items()}
    NUMBERS.write_text(json.dumps(numbers, indent=1, sort_keys=True) + "\n")
    print("wrote", NUMBERS)
