/* ----------------------------------------------------------------------
   pair_style gran/mn's reports of overlaps too deep (granmn_overlap_reports.h).
------------------------------------------------------------------------- */

#include "granmn_overlap_reports.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "granmn_flat_arrays.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <string>

using namespace LAMMPS_NS;

namespace granmn {

// The law has lost two disks whose centres came within the larger radius: their normal flips
// once the centres cross, and they fly apart on swapped sides.
// A pair whose radii the cut-off of their types does not cover was not in the neighbour list
// when they met (atoms larger than the run was set up for): no step or stiffness helps. An
// atom of diameter 0 has its centre inside the other at its first touch. A pair that got
// there within one step (its overlap is less than the step's motion) needs a finer step: one
// with ten steps across the smaller radius r. Otherwise the spring was already acting and is
// too soft: a head-on approach at speed v stops within an overlap v/w (undamped; w^2 = 2 kn for
// two disks, kn against a bump), which must stay below r.
void report_passed_through(LAMMPS *lmp, const mn::Law &law, const BumpTypes &bumps,
                           double **cutsq, int i, int j, double r)
{
  Atom *atom = lmp->atom;
  Domain *domain = lmp->domain;
  Error *error = lmp->error;
  Update *update = lmp->update;
  const tagint *tag = atom->tag;
  if (r == 0.0)
    error->one(FLERR, "pair_style gran/mn: atoms {} and {} are at the same position: the "
                      "contact has no normal", tag[i], tag[j]);
  const double radius_min = MIN(atom->radius[i], atom->radius[j]);
  const double delta = atom->radius[i] + atom->radius[j] - r;
  if (update->setupflag)
    error->one(FLERR, "pair_style gran/mn: atoms {} and {} overlap by {:.6g}, more than the "
                      "smaller radius {:.6g}: the centre of one is inside the other (placed so?)",
                      tag[i], tag[j], delta, radius_min);
  double **x = atom->x, **v = atom->v;
  double dot = 0.0;
  for (int c = 0; c < domain->dimension; c++) dot += (x[i][c] - x[j][c]) * (v[i][c] - v[j][c]);
  const double vn = fabs(dot) / r;
  const bool boundary = bumps.is_bump(atom->type[i]) || bumps.is_bump(atom->type[j]);
  const double dt = update->dt;
  const int itype = atom->type[i], jtype = atom->type[j];
  const double radsum = atom->radius[i] + atom->radius[j];
  std::string cause;
  double speed = vn;
  if (radsum * radsum > cutsq[itype][jtype]) {
    cause = fmt::format("the pair style's cut-off for atom types {} and {}, {:.6g}, is less "
                        "than their radii's sum {:.6g}, so they were not in the neighbor list "
                        "when they met: atoms larger than the cut-offs were set for (at the "
                        "start of the run, from the atoms present and the radii fix pour and "
                        "fix deposit insert) came in or grew during the run; create or set "
                        "them before the run, or insert them with fix pour or fix deposit",
                        itype, jtype, sqrt(cutsq[itype][jtype]), radsum);
  } else if (radius_min == 0.0) {
    cause = fmt::format("atom {} has diameter 0 (a point particle), so its centre is inside "
                        "the other at its first touch: the law is for {}; give it a diameter",
                        atom->radius[i] == 0.0 ? tag[i] : tag[j],
                        domain->dimension == 3 ? "spheres" : "disks");
  } else if (vn * dt >= delta) {
    cause = fmt::format("they got there within one step (the time step {:.6g} moves them by "
                        "{:.6g}): use a time step below {:.6g} (ten steps across the radius)",
                        dt, vn * dt, 0.1 * radius_min / vn);
  } else {
    // the speed they met at, from the energy of the normal motion: damping only lowers it
    const double omega2 = (boundary ? 1.0 : 2.0) * law.material.kn;
    speed = sqrt(vn * vn + omega2 * delta * delta);
    const double stopped_within = speed / sqrt(omega2);
    cause = fmt::format("kn = {:.6g} stops them only within an overlap of {:.6g}: it takes "
                        "kn > {:.6g} to stop them within the radius",
                        law.material.kn, stopped_within,
                        law.material.kn * pow(stopped_within / radius_min, 2));
  }
  error->one(FLERR, "pair_style gran/mn: atoms {} and {} have passed through each other at step "
                    "{}: the centre of one is inside the other (overlap {:.6g} > {:.6g}, the "
                    "smaller radius); they met at a relative speed of about {:.6g} ({}); {}",
             tag[i], tag[j], update->ntimestep, delta, radius_min, speed,
             boundary ? (domain->dimension == 3 ? "a sphere and a bump" : "a disk and a bump")
                      : (domain->dimension == 3 ? "two spheres" : "two disks"),
             cause);
}

// Run at a run's setup, from the list just built: LAMMPS says nothing of such pairs.
void warn_deep_overlaps(LAMMPS *lmp, const mn::Law &law, const BumpTypes &bumps,
                        const NeighList *list)
{
  Atom *atom = lmp->atom;
  const double *x = rows(atom->x), *radius = atom->radius;
  const tagint *tag = atom->tag;
  const int dimension = lmp->domain->dimension, nlocal = atom->nlocal;
  MPI_Comm world = lmp->world;
  bigint count = 0;
  // the deepest here: its overlap as a fraction of the smaller radius, the tags (the smaller
  // first), the overlap, that radius, its release speed
  double deepest[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = list->firstneigh[i][jj] & NEIGHMASK;
      double rsq = 0.0;
      for (int c = 0; c < dimension; c++) {
        const double d = x[row_start(i, 3) + c] - x[row_start(j, 3) + c];
        rsq += d * d;
      }
      const double delta = radius[i] + radius[j] - sqrt(rsq);
      if (!mn::deep_overlap(delta, radius[i], radius[j])) continue;
      // newton off: a pair with a ghost is listed by both of its processes; counted by one
      if (!lmp->force->newton_pair && j >= nlocal && tag[i] > tag[j]) continue;
      count++;
      const double radius_min = MIN(radius[i], radius[j]);
      if (delta / radius_min <= deepest[0]) continue;
      const bool boundary = bumps.is_bump(atom->type[i]) || bumps.is_bump(atom->type[j]);
      const double found[6] = {delta / radius_min, double(MIN(tag[i], tag[j])),
                               double(MAX(tag[i], tag[j])), delta, radius_min,
                               mn::release_speed(law, delta, boundary)};
      for (int k = 0; k < 6; k++) deepest[k] = found[k];
    }
  }
  bigint all = 0;
  MPI_Allreduce(&count, &all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (all == 0) return;
  // the deepest from the first process that holds it
  double fraction = 0.0;
  MPI_Allreduce(&deepest[0], &fraction, 1, MPI_DOUBLE, MPI_MAX, world);
  // not const: a serial LAMMPS's STUBS mpi.h declares the send buffers `void *`
  int mine = deepest[0] == fraction ? lmp->comm->me : lmp->comm->nprocs;
  int holder = 0;
  MPI_Allreduce(&mine, &holder, 1, MPI_INT, MPI_MIN, world);
  MPI_Bcast(deepest, 6, MPI_DOUBLE, holder, world);
  if (lmp->comm->me == 0)
    lmp->error->warning(FLERR, "pair_style gran/mn: {} pair(s) of particles overlap by more "
                               "than {:g} of the smaller radius at the start of the run; the "
                               "deepest, atoms {:.0f} and {:.0f}, by {:.6g} ({:.3g} of radius "
                               "{:.6g}): released, it drives them apart at up to {:.3g} (placed "
                               "closer than their radii's sum?)",
                        all, mn::DEEP_OVERLAP_FRACTION, deepest[1], deepest[2], deepest[3],
                        deepest[0], deepest[4], deepest[5]);
}

}    // namespace granmn
