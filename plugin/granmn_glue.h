/* -*- c++ -*- ----------------------------------------------------------
   Small pieces of LAMMPS glue shared by the gran/mn styles.
------------------------------------------------------------------------- */

#ifndef LMP_GRANMN_GLUE_H
#define LMP_GRANMN_GLUE_H

#include "error.h"
#include "lammps.h"
#include "modify.h"

#include "mn_contact.h"

namespace granmn {

// The paper's integrator (fix nve/ab2) if a deck uses it, else LAMMPS's velocity Verlet.
inline mn::Integrator integrator_in_use(LAMMPS_NS::Modify *modify)
{
  return modify->find_fix_by_style("^nve/ab2") >= 0 ? mn::Integrator::AdamsBashforth2
                                                    : mn::Integrator::VelocityVerlet;
}

inline const char *integrator_name(mn::Integrator integrator)
{
  return integrator == mn::Integrator::AdamsBashforth2 ? "Adams-Bashforth 2" : "velocity Verlet";
}

// A time step beyond the stability limit of the stiffest contact mode is an error; one that
// resolves a binary collision with fewer than 10 steps is worth a warning.
inline void check_timestep(LAMMPS_NS::LAMMPS *lmp, const char *who, double dt, double dt_max,
                           double tau_c, mn::Integrator integrator)
{
  if (dt > dt_max)
    lmp->error->all(FLERR,
                    "{}: timestep {} exceeds the stability limit {:.6g} of {} for the stiffest "
                    "contact (tau_c = {:.6g}); the paper uses dt = tau_c/100",
                    who, dt, dt_max, integrator_name(integrator), tau_c);
  if (dt > 0.1 * tau_c)
    lmp->error->warning(FLERR,
                        "{}: timestep {} resolves a collision (tau_c = {:.6g}) with fewer "
                        "than 10 steps",
                        who, dt, tau_c);
}

}    // namespace granmn

#endif
