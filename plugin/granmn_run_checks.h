/* -*- c++ -*- ----------------------------------------------------------
   What the gran/mn styles check of a run at init: the integrator in use, that it integrates
   the shape the law is derived for, and the time step against the law's stability limit.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_RUN_CHECKS_H
#define LMP_GRANMN_RUN_CHECKS_H

#include "domain.h"
#include "error.h"
#include "fix_nve_sphere.h"
#include "granmn_compat.h"
#include "lammps.h"
#include "modify.h"
#include "utils.h"

#include "mn_integration.h"

#include <cstring>
#include <string>
#include <vector>

namespace granmn {

// The names under which fix nve/disc/mn (and nve/ab2) answers Fix::extract (dim 0, read
// only): its scheme (a const mn::Integrator *), and whether it decides the neighbour-list
// builds (neigh_check yes; a const bool *).
constexpr const char *INTEGRATOR_EXTRACT_NAME = "granmn_integrator";
constexpr const char *NEIGH_CHECK_EXTRACT_NAME = "granmn_neigh_check";

// The fixes that answer those names: asked alone, as some styles' extract() fails on a name
// they do not know (fix langevin/drude's).
inline std::vector<LAMMPS_NS::Fix *> disc_integrators(LAMMPS_NS::Modify *modify)
{
  std::vector<LAMMPS_NS::Fix *> fixes = fixes_by_style(modify, "^nve/disc/mn$");
  for (LAMMPS_NS::Fix *fix : fixes_by_style(modify, "^nve/ab2$")) fixes.push_back(fix);
  return fixes;
}

// The paper's integrator if a deck uses it (fix nve/ab2, fix nve/disc/mn scheme ab2), else
// velocity Verlet (LAMMPS's fix nve/sphere, fix nve/disc/mn's default).
inline mn::Integrator integrator_in_use(LAMMPS_NS::Modify *modify)
{
  for (LAMMPS_NS::Fix *fix : disc_integrators(modify)) {
    int dim = 0;
    const auto *scheme = static_cast<const mn::Integrator *>(
        fix->extract(INTEGRATOR_EXTRACT_NAME, dim));
    if (scheme && *scheme == mn::Integrator::AdamsBashforth2)
      return mn::Integrator::AdamsBashforth2;
  }
  return mn::Integrator::VelocityVerlet;
}

// Whether a fix decides when the neighbour lists are built (fix nve/disc/mn neigh_check yes).
inline bool neighbor_builds_checked(LAMMPS_NS::Modify *modify)
{
  for (LAMMPS_NS::Fix *fix : disc_integrators(modify)) {
    int dim = 0;
    const auto *checks = static_cast<const bool *>(fix->extract(NEIGH_CHECK_EXTRACT_NAME, dim));
    if (checks && *checks) return true;
  }
  return false;
}

// FixNVESphere keeps its moment-of-inertia prefactor (2/5 sphere, 1/2 disc) protected; a
// pointer to the member formed through a derived class reads it without changing LAMMPS.
struct NVESphereInertia : LAMMPS_NS::FixNVESphere {
  static double of(LAMMPS_NS::Fix *fix)
  {
    return static_cast<LAMMPS_NS::FixNVESphere *>(fix)->*(&NVESphereInertia::inertia);
  }
};

// The law's tangential parameters assume the dimension's shape of inertia (dimension_q). In
// 2D a fix nve/sphere without 'disc' integrates the spins of spheres, and beta comes out wrong
// (0.661 for 0.7); in 3D it integrates spheres, as the law assumes (LAMMPS refuses 'disc' in 3D).
inline void check_disc_integration(LAMMPS_NS::LAMMPS *lmp, const char *who)
{
  const bool three_d = lmp->domain->dimension == 3;
  for (LAMMPS_NS::Fix *fix : fixes_by_style(lmp->modify, "^nve/sphere$")) {
    const double inertia = NVESphereInertia::of(fix);
    if (!three_d && inertia != 0.5)
      lmp->error->all(FLERR,
                      "{}: fix {} (nve/sphere) integrates spheres; the law is for disks: add "
                      "the keyword disc (fix {} ... nve/sphere disc)",
                      who, fix->id, fix->id);
    if (three_d && inertia != 0.4)
      lmp->error->all(FLERR,
                      "{}: fix {} (nve/sphere) integrates a moment of inertia {} m r^2; in "
                      "dimension 3 the law is derived for solid spheres (2/5 m r^2): leave out "
                      "the keyword disc", who, fix->id, inertia);
  }
}

inline const char *integrator_name(mn::Integrator integrator)
{
  return integrator == mn::Integrator::AdamsBashforth2 ? "Adams-Bashforth 2" : "velocity Verlet";
}

// A time step beyond the stability limit of the stiffest contact mode is an error that names
// the mode and the step that works (below tau_c/100 when e or beta near 0 damps a mode hard);
// one that resolves a binary collision with fewer than 10 steps is worth a warning.
inline void check_timestep(LAMMPS_NS::LAMMPS *lmp, const char *who, double dt, const mn::Law &law,
                           mn::Integrator integrator)
{
  if (mn::amplifies_undamped_mode(law, integrator))
    lmp->error->warning(FLERR,
                        "{}: Adams-Bashforth 2 slowly amplifies an undamped contact mode (e = 1, "
                        "or beta = 1 with friction): collisions are fine at this step, contacts "
                        "that last gain energy; velocity Verlet keeps them", who);
  const mn::StabilityLimit limit = mn::stability_limit(law, integrator);
  const double paper_dt = 0.01 * law.tau_c;
  // the modes are named for disks; in 3D they are those of spheres (and do not depend on q)
  std::string mode = mn::mode_name(limit.mode);
  const size_t disks = mode.find("disks");
  if (lmp->domain->dimension == 3 && disks != std::string::npos) mode.replace(disks, 5, "spheres");
  if (dt > limit.dt)
    lmp->error->all(FLERR,
                    "{}: timestep {} exceeds the stability limit {:.6g} of {} for the stiffest "
                    "contact mode, {}: use a timestep below {:.6g} ({})",
                    who, dt, limit.dt, integrator_name(integrator), mode,
                    limit.dt,
                    limit.dt < paper_dt
                        ? fmt::format("the paper's tau_c/100 = {:.6g} is too coarse here: e or "
                                      "beta close to 0 damps this mode so hard that it needs a "
                                      "finer step", paper_dt)
                        : fmt::format("the paper uses tau_c/100 = {:.6g}", paper_dt));
  if (dt > 0.1 * law.tau_c)
    lmp->error->warning(FLERR,
                        "{}: timestep {} resolves a collision (tau_c = {:.6g}) with fewer "
                        "than 10 steps",
                        who, dt, law.tau_c);
}

}    // namespace granmn

#endif
