"""What each scene is, for the analysis: the one place that says how a scene is normalised,
which part of a run is averaged, what extra observable it has and how its figures look
(docs/model.md sections 5-7). The modules ask a Scene; none tests a scene's name."""
from dataclasses import dataclass, replace


@dataclass(frozen=True)
class Guide:
    """A guide line on the stiffness figure: quantity ~ kn^exponent through the first point."""
    panel: str          # "rates" or "times"
    quantity: str
    exponent: float
    label: str


@dataclass(frozen=True)
class Scene:
    name: str
    title: str
    # average only the steady parts selected by the paper's rule (else the whole window, which
    # then must not end at rest: a run that came to rest has no steady motion to average)
    selects_steady_parts: bool = False
    # N_w, t_w per disk that touched the boundary (the bottom layer), not per disk
    boundary_per_bottom_layer: bool = False
    # the single disk's v_y period and time to pass one bump (bump_spacing / mean v_x), from
    # trajectory.txt; bump_spacing: the deck's spacing of the bumps' centres
    has_period: bool = False
    bump_spacing: float = None
    # collision rates against ln kn (a log law) rather than log-log
    rates_log_law: bool = False
    guides: tuple = ()
    # E's stiff value: its mean over kn >= stiff_from (the single disk: the paper's 1/k_n <
    # 1e-7); the report says from which kn E reaches it (study.crossover). 0: not measured.
    stiff_from: float = 0.0
    notes: tuple = ()
    # the slope and the system, as the transition study (docs/transition.md) names the scene
    base: str = ""
    # what the flowing particles are, for labels (the observables are per particle)
    particle: str = "disk"
    # the quantities the hard-sphere-limit rule (postprocess limit, docs/hard_sphere_limit.md)
    # decides on in the scene's runs (empty: the rule is not for it); limit_levels: {name: (low,
    # high)} the energy levels per particle its flows sit at, within which the rule is applied
    # again (empty: no levels, that step is skipped)
    limit_quantities: tuple = ()
    limit_levels: tuple = ()

    @property
    def decides_limit(self):
        return bool(self.limit_quantities)


SCENES = {s.name: s for s in (
    Scene("single_disk", "single disk on a bumpy slope", has_period=True, bump_spacing=1.002,
          rates_log_law=True, stiff_from=1e7),
    # its disks' contacts are binary (t_c - N_c tau_c < 0: Verlet's slightly short contacts),
    # the boundary's are not: the rule decides on t_w - N_w tau_w alone
    Scene("collisional_flow", "collisional flow",
          guides=(Guide("times", "t_c", -0.5, "k_n^-1/2 guide"),),
          base="bumpy base, 50 disks", limit_quantities=("mc_w",)),
    Scene("frictional_flow", "frictional flow", selects_steady_parts=True,
          boundary_per_bottom_layer=True,
          guides=(Guide("rates", "N_c", 0.4, "k_n^0.4 guide (the paper's)"),),
          notes=("N_w and t_w are per disk of the bottom layer (disks that touched the floor in "
                 "the averaging window; the paper: during the averaging span).",),
          base="flat base, 100 polydisperse disks",
          limit_quantities=("mc_c", "mc_w", "t_multiple"),
          # the frictional flow sits near E ~ 0.4, ~0.65, ~0.95 per disk
          limit_levels=(("low", (0.3, 0.5)), ("middle", (0.5, 0.8)), ("high", (0.8, 1.2)))),
    # inputs/chute_3d.lmp: a dense frictional flow and a dilute collisional one are two
    # parameter sets of one deck (inputs/sweeps/chute_3d.toml), averaged alike: over the window
    # after average_start (the 2D frictional flow's energy range [0.4, 0.8] and spans > 500
    # belong to that scene), a run that came to rest refused; per flowing sphere, N_w and t_w
    # per sphere that touched the base (in the dilute flow, all of them). Its dense flow's E
    # moves smoothly with k_n (0.53 -> 0.40 per sphere over three decades, docs/three_d.md):
    # no levels to split the limit rule's runs by
    Scene("chute_3d", "3D chute", boundary_per_bottom_layer=True,
          guides=(Guide("rates", "N_c", 0.4, "k_n^0.4 guide (the 2D paper's)"),
                  Guide("times", "t_c", -0.5, "k_n^-1/2 guide")),
          notes=("Spheres (3D). N_w and t_w are per sphere that touched the base (the fixed "
                 "spheres) in the averaging window.",),
          base="rough base of fixed spheres, 3D", particle="sphere",
          limit_quantities=("mc_c", "mc_w", "t_multiple")),
)}


def scene(name):
    """The Scene of a name, or KeyError naming the known ones."""
    try:
        return SCENES[name]
    except KeyError:
        raise KeyError(f"unknown scene '{name}' (expected one of {', '.join(SCENES)})") from None


def transition_scene(name):
    """A scene as the transition study averages it (docs/transition.md): away from sin theta =
    0.20 the paper's energy window [0.4, 0.8] means nothing, so a run classified as flowing is
    averaged over its whole span after the transient, as the collisional flow is; the
    normalisations stay the scene's."""
    return replace(scene(name), selects_steady_parts=False)
