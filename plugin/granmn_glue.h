/* -*- c++ -*- ----------------------------------------------------------
   Small pieces of LAMMPS glue shared by the gran/mn styles.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_GLUE_H
#define LMP_GRANMN_GLUE_H

#include "domain.h"
#include "error.h"
#include "fix_nve_disc_mn.h"
#include "fix_nve_sphere.h"
#include "granmn_compat.h"
#include "lammps.h"
#include "modify.h"
#include "update.h"
#include "utils.h"

#include "mn_contact_events.h"
#include "mn_integration.h"

#include <cstring>
#include <string>

namespace granmn {

// The time over which a force evaluation advances u_t: none for the forces LAMMPS re-evaluates
// in a run's setup (u_t must not advance twice for one step).
inline double history_dt(LAMMPS_NS::Update *update)
{
  return update->setupflag ? 0.0 : update->dt;
}

// The paper's integrator if a deck uses it (fix nve/ab2, fix nve/disc/mn scheme ab2), else
// velocity Verlet (LAMMPS's fix nve/sphere, fix nve/disc/mn's default).
inline mn::Integrator integrator_in_use(LAMMPS_NS::Modify *modify)
{
  for (LAMMPS_NS::Fix *fix : all_fixes(modify)) {
    const auto *disc = dynamic_cast<const LAMMPS_NS::FixNVEDiscMN *>(fix);
    if (disc && disc->scheme() == mn::Integrator::AdamsBashforth2)
      return mn::Integrator::AdamsBashforth2;
  }
  return mn::Integrator::VelocityVerlet;
}

// FixNVESphere keeps its moment-of-inertia prefactor (2/5 sphere, 1/2 disc) protected; a
// pointer to the member formed through a derived class reads it without changing LAMMPS.
struct NVESphereInertia : LAMMPS_NS::FixNVESphere {
  static double of(LAMMPS_NS::Fix *fix)
  {
    return static_cast<LAMMPS_NS::FixNVESphere *>(fix)->*(&NVESphereInertia::inertia);
  }
};

// The shape of inertia the law is derived for (mn::derive's q): the dimension decides it, as
// it decides what atom_style sphere's particles are. In 2D disks (I = m r^2/2, the paper's
// law), in 3D solid spheres (I = 2 m r^2/5, what fix nve/sphere integrates in 3D).
inline double dimension_q(LAMMPS_NS::LAMMPS *lmp)
{
  return lmp->domain->dimension == 3 ? mn::SOLID_SPHERE_Q : mn::DISC_Q;
}

// u_t's components: a scalar along t in 2D, a vector in the tangent plane in 3D.
inline int ut_width(LAMMPS_NS::LAMMPS *lmp)
{
  return lmp->domain->dimension == 3 ? 3 : 1;
}

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

// Where a contact's values sit in the storage of the style that keeps it (-1: not kept),
// handed out at init: in the pair style's neighbour history (pair_history_layout), in the
// wall fix's per-atom state for each wall side (wall_state_layout). The styles hand the
// record to the contact observer (mn_contact_events.h), which knows what a record holds, not
// where it is.
struct ContactLayout {
  int ut_width = 1;        // u_t's components: one in 2D, three in 3D (granmn::ut_width)
  int ut = -1;             // u_t, ut_width values (mu > 0)
  int vt_previous = -1;    // v_t at the previous force evaluation, ut_width values: Adams-
                           // Bashforth 2's rule for u_t (mu > 0)
  int record = -1;         // the observer's record (RECORD_SIZE values)
  int touching = -1;       // 1 while in contact (a wall side; a pair has its neighbour flag)
  int size = 0;            // values the storage holds: per contact (pair), per atom (wall)
};

// A contact's neighbour history: its parts one after the other, only those kept (restart files
// hold the history in this order).
inline ContactLayout pair_history_layout(bool friction, bool adams_bashforth, bool counters,
                                         int ut_width = 1)
{
  ContactLayout layout;
  layout.ut_width = ut_width;
  auto take = [&layout](bool kept, int width) {
    if (!kept) return -1;
    layout.size += width;
    return layout.size - width;
  };
  layout.ut = take(friction, layout.ut_width);
  layout.vt_previous = take(friction && adams_bashforth, layout.ut_width);
  layout.record = take(counters, RECORD_SIZE);
  return layout;
}

// An atom's row in the wall fix, both sides: each part at a place of its own whether kept or
// not (u_t of both sides, each side's record and flag, the previous v_t of both), so that a
// part kept from a later run on moves no other (restart files hold the rows so); `size` is
// the whole row's. A style keeps the row up to its last part kept. u_t and v_t have
// ut_width values each.
inline void wall_state_layout(ContactLayout side[2], int ut_width = 1)
{
  side[0].ut_width = side[1].ut_width = ut_width;
  int next = 0;
  for (int s : {0, 1}) {
    side[s].ut = next;
    next += side[s].ut_width;
  }
  for (int s : {0, 1}) {
    side[s].record = next;
    next += RECORD_SIZE;
    side[s].touching = next++;
  }
  for (int s : {0, 1}) {
    side[s].vt_previous = next;
    next += side[s].ut_width;
  }
  side[0].size = side[1].size = next;
}

// The name under which pair_style gran/mn hands out its law through Pair::extract (a
// const mn::Law *, dim 0; read only): fix wall/gran/mn takes what its line does not give.
constexpr const char *LAW_EXTRACT_NAME = "granmn_law";

// The law's keywords on a style's line: a number of the material, or an option (a flag).
struct LawKeyword {
  const char *name;
  double mn::Material::*number;
  bool mn::Options::*option;
};
constexpr LawKeyword LAW_KEYWORDS[] = {
    {"kn", &mn::Material::kn, nullptr},     {"e", &mn::Material::e, nullptr},
    {"beta", &mn::Material::beta, nullptr}, {"mu", &mn::Material::mu, nullptr},
    {"limit_damping", nullptr, &mn::Options::limit_damping},
    {"coulomb_cutback", nullptr, &mn::Options::coulomb_cutback}};
constexpr int N_LAW_KEYWORDS = sizeof(LAW_KEYWORDS) / sizeof(LAW_KEYWORDS[0]);

// The law keywords a style's arguments hold: their values, and which were given.
struct LawArguments {
  mn::Material material{0.0, 0.0, 0.0, 0.0};
  mn::Options options;
  bool given[N_LAW_KEYWORDS] = {};

  bool all_numbers_given() const
  {
    for (int k = 0; k < N_LAW_KEYWORDS; k++)
      if (LAW_KEYWORDS[k].number && !given[k]) return false;
    return true;
  }
};

// Reads the law keyword at arg[iarg] ("kn K", ..., "limit_damping"); returns how many
// arguments it used, 0 if arg[iarg] is none of them.
inline int parse_law_keyword(LAMMPS_NS::LAMMPS *lmp, const char *command, int narg, char **arg,
                             int iarg, LawArguments &law)
{
  for (int k = 0; k < N_LAW_KEYWORDS; k++) {
    const LawKeyword &keyword = LAW_KEYWORDS[k];
    if (strcmp(arg[iarg], keyword.name) != 0) continue;
    if (keyword.option) {
      law.options.*keyword.option = law.given[k] = true;
      return 1;
    }
    if (law.given[k])
      lmp->error->all(FLERR, "Illegal {} command: {} given twice", command, keyword.name);
    law.given[k] = true;
    if (iarg + 2 > narg)
      lmp->error->all(FLERR, "Illegal {} command: {} needs a value", command, keyword.name);
    law.material.*keyword.number = LAMMPS_NS::utils::numeric(FLERR, arg[iarg + 1], false, lmp);
    return 2;
  }
  return 0;
}

// The law of a material and options for particles of shape q (dimension_q), checked: an
// error of `command` says what is wrong.
inline mn::Law checked_law(LAMMPS_NS::LAMMPS *lmp, const char *command,
                           const mn::Material &material, const mn::Options &options, double q)
{
  const char *problem = mn::material_error(material);
  if (problem) lmp->error->all(FLERR, "Illegal {} command: {}", command, problem);
  const mn::Law law = mn::derive(material, options, q);
  problem = mn::law_error(law);
  if (problem)
    lmp->error->all(FLERR, "Illegal {} command: {} (kn = {})", command, problem, material.kn);
  return law;
}

// The law the arguments give, what they do not give taken from `defaults` (nullptr: every
// number must be given, an option not given is off).
inline mn::Law law_from_arguments(LAMMPS_NS::LAMMPS *lmp, const char *command,
                                  const LawArguments &arguments, const mn::Law *defaults)
{
  mn::Material material = arguments.material;
  mn::Options options = arguments.options;
  for (int k = 0; k < N_LAW_KEYWORDS; k++) {
    const LawKeyword &keyword = LAW_KEYWORDS[k];
    if (arguments.given[k]) continue;
    if (keyword.option && defaults) options.*keyword.option = defaults->options.*keyword.option;
    if (keyword.number && defaults)
      material.*keyword.number = defaults->material.*keyword.number;
    else if (keyword.number)
      lmp->error->all(FLERR, "Illegal {} command: {} must be given", command, keyword.name);
  }
  return checked_law(lmp, command, material, options, dimension_q(lmp));
}

}    // namespace granmn

#endif
