/* ----------------------------------------------------------------------
   fix nve/ab2: v(t+dt) = v + dt (3/2 a(t) - 1/2 a(t-dt)),
                x(t+dt) = x + dt/2 (v(t) + v(t+dt)), the same for spins (disks, I = m r^2/2).
   The force at a step sees that step's positions and velocities (no half-step velocity).
------------------------------------------------------------------------- */

#include "fix_nve_ab2.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "update.h"

#include "mn_contact.h"

using namespace LAMMPS_NS;
using namespace FixConst;

// fix ID group nve/ab2
FixNVEAB2::FixNVEAB2(LAMMPS *lmp, int narg, char **arg) : FixPerAtomState(lmp, narg, arg)
{
  if (narg != 3) error->all(FLERR, "Illegal fix nve/ab2 command: it takes no arguments");
  if (domain->dimension != 2)
    error->all(FLERR, "Fix nve/ab2 integrates disks: it requires dimension 2");
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Fix nve/ab2 requires atom attributes radius, rmass, omega, torque "
                      "(atom_style sphere)");
  time_integrate = 1;
  allocate_state(NSTATE);
}

int FixNVEAB2::setmask()
{
  return INITIAL_INTEGRATE;
}

void FixNVEAB2::init()
{
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Fix nve/ab2 does not support run_style respa");
  // a point particle has no moment of inertia: its spin would be torque/0
  int points = 0;
  for (int i = 0; i < atom->nlocal; i++)
    if ((atom->mask[i] & groupbit) && atom->radius[i] == 0.0) points++;
  int points_all = 0;
  MPI_Allreduce(&points, &points_all, 1, MPI_INT, MPI_SUM, world);
  if (points_all)
    error->all(FLERR, "Fix nve/ab2 integrates disks: {} atoms of its group have diameter 0 "
                      "(point particles)", points_all);
}

void FixNVEAB2::initial_integrate(int)
{
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  double **omega = atom->omega;
  double **torque = atom->torque;
  const double *radius = atom->radius;
  const double *rmass = atom->rmass;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double dt = update->dt;
  const double ftm2v = force->ftm2v;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *prev = state[i];
    const double a[3] = {ftm2v * f[i][0] / rmass[i], ftm2v * f[i][1] / rmass[i],
                         ftm2v * torque[i][2] / (0.5 * rmass[i] * radius[i] * radius[i])};
    // The first step has no previous acceleration: it takes a(t - dt) = a(t), an Euler step.
    if (prev[HAS_PREVIOUS] == 0.0) {
      for (int k = 0; k < 3; k++) prev[k] = a[k];
      prev[HAS_PREVIOUS] = 1.0;
    }
    for (int k = 0; k < 2; k++) {
      const double v_new = mn::ab2_velocity(v[i][k], a[k], prev[k], dt);
      x[i][k] = mn::trapezoidal_position(x[i][k], v[i][k], v_new, dt);
      v[i][k] = v_new;
    }
    omega[i][2] = mn::ab2_velocity(omega[i][2], a[2], prev[ALPHA], dt);
    for (int k = 0; k < 3; k++) prev[k] = a[k];
  }
}

