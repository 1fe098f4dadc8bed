/* ----------------------------------------------------------------------
   pair_style gran/mn's checks of the input (granmn_pair_checks.h).
------------------------------------------------------------------------- */

#include "granmn_pair_checks.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "granmn_run_checks.h"
#include "neighbor.h"
#include "pair.h"

using namespace LAMMPS_NS;

namespace granmn {

void check_sphere_attributes(LAMMPS *lmp)
{
  const Atom *atom = lmp->atom;
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    lmp->error->all(FLERR, "Pair style gran/mn requires atom attributes radius, rmass, omega, "
                           "torque (atom_style sphere)");
}

// One law per simulation: fix wall/gran/mn, fix contacts/mn and the v_mn_* variables take
// it from the gran/mn style. pair_style hybrid declares its sub-styles in order, so a second
// gran/mn finds the first here.
void check_one_gran_mn(LAMMPS *lmp, const Pair *self)
{
  const Pair *first = lmp->force->pair_match("gran/mn", 1);
  if (first && first != self)
    lmp->error->all(FLERR, "pair_style gran/mn: pair_style hybrid holds gran/mn twice; the "
                           "gran/mn styles support one (fix wall/gran/mn, fix contacts/mn and "
                           "the v_mn_* variables take their law from it): give one gran/mn "
                           "sub-style");
}

// A fix that decides the builds (fix nve/disc/mn neigh_check yes) asks for them itself.
void warn_builds_once(LAMMPS *lmp)
{
  if (lmp->neighbor->build_once && !neighbor_builds_checked(lmp->modify) && lmp->comm->me == 0)
    lmp->error->warning(FLERR, "pair_style gran/mn: neigh_modify once yes builds the neighbor "
                               "list only at the start of a run: disks that come into contact "
                               "later are never seen (no force, no contact); leave out 'once "
                               "yes'");
}

// In 2D the law measures distances in the plane, the neighbor list in 3D: an atom off z = 0
// would be missed by disks it touches, which then get inside it. Atoms come in at a build
// (fix deposit places them at random z within its region): checked after each.
void check_in_plane(LAMMPS *lmp)
{
  double **x = lmp->atom->x;
  for (int i = 0; i < lmp->atom->nlocal; i++)
    if (x[i][2] != 0.0)
      lmp->error->one(FLERR, "pair_style gran/mn: atom {} is at z = {:.6g} in a 2D simulation, "
                             "where every disk must be at z = 0 (the neighbor list measures "
                             "distances in 3D and would miss its contacts); fix deposit places "
                             "atoms at random z within its region: give the region a z extent "
                             "of 0 0",
                      lmp->atom->tag[i], x[i][2]);
}

// LAMMPS restores per-pair history with the size of the new run: a different size would
// misread every partner, so the run must keep mu > 0 (or not), fix contacts/mn (or not) and
// the integrator.
void check_history_size(LAMMPS *lmp, int needed, int set_up, int restored)
{
  if (set_up >= 0 && needed != set_up)
    lmp->error->all(FLERR, "pair_style gran/mn: its contact history was set up for a different "
                           "mu, fix contacts/mn or integrator (fix contacts/mn energy yes keeps "
                           "the contacts' energies; Adams-Bashforth 2, fix nve/ab2 or fix "
                           "nve/disc/mn scheme ab2, keeps one more value per contact when mu > "
                           "0); define fix contacts/mn, mu and the integrator before the first "
                           "run");
  if (set_up < 0 && restored >= 0 && needed != restored)
    lmp->error->all(FLERR, "pair_style gran/mn: the restart file holds {} history values per "
                           "contact, this run needs {}: keep mu zero or non-zero, define fix "
                           "contacts/mn (or not) with energy yes (or not) and use the scheme "
                           "(Adams-Bashforth 2 or not) as in the run that wrote it",
                    restored, needed);
}

// A fix deform with remap v shifts the velocities of ghosts across a periodic boundary by the
// box's rate, in LAMMPS's own ghost communication only. Known only at a run's setup, after the
// domain's init.
void check_deform_remap(LAMMPS *lmp, bool sends_ghost_velocity)
{
  if (sends_ghost_velocity && lmp->domain->deform_vremap)
    lmp->error->all(FLERR, "Pair style gran/mn with fix deform remap v requires comm_modify vel "
                           "yes (the ghosts' velocities then carry the box's rate)");
}

// Bonded atoms (a molecular atom style): LAMMPS keeps a 1-2, 1-3 or 1-4 pair in the neighbor
// list, flagged, unless its special_bonds lj and coul weights are both 0 or both 1
// (Neighbor::special_flag 2), and its granular styles (2025 on) skip such a pair at lj 0 and
// scale its force otherwise. The law weighs no contact: the pair would touch in full.
// (LAMMPS 2021's granular lists keep every bonded pair, unflagged, for its own styles as for
// this one.) Known only at a run's setup, after the neighbor's init.
void check_special_bonds(LAMMPS *lmp)
{
  if (lmp->atom->molecular == Atom::ATOMIC) return;
  const Force *force = lmp->force;
  for (int level = 1; level <= 3; level++)
    if (lmp->neighbor->special_flag[level] == 2 && force->special_lj[level] != 1.0)
      lmp->error->all(FLERR, "pair_style gran/mn: special_bonds lj {:g} coul {:g} keeps 1-{} "
                             "pairs in the neighbor list with a weight the law does not apply (a "
                             "contact of this style is full or absent): use lj 0 with coul 0, or "
                             "lj 1",
                      force->special_lj[level], force->special_coul[level], level + 1);
}

}    // namespace granmn
