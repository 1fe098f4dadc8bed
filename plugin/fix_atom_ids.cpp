/* ----------------------------------------------------------------------
   fix GRANMN/ATOM_IDS: atoms whose ID changed under pair_style gran/mn's contact history.
------------------------------------------------------------------------- */

#include "fix_atom_ids.h"

#include "atom.h"
#include "comm.h"
#include "error.h"

using namespace LAMMPS_NS;

FixAtomIDs::FixAtomIDs(LAMMPS *lmp, int narg, char **arg) : FixPerAtomState(lmp, narg, arg)
{
  register_state(1);
  wd_header = 0;    // an atom's ID is in any data file
}

// A run's init, after the pair style's (which defined this fix at its first one).
void FixAtomIDs::init()
{
  const bigint changed = renumbered();
  if (changed && comm->me == 0)
    error->warning(FLERR, "pair_style gran/mn: {} atoms have other IDs than in the last run "
                          "(delete_atoms compress yes?): their contacts lost their history "
                          "(u_t, counters); use delete_atoms ... compress no", changed);
}

// A new atom has no ID yet when its arrays are set: 0 until the next check records it.
void FixAtomIDs::set_arrays(int i)
{
  state[i][0] = 0.0;
}

bigint FixAtomIDs::renumbered()
{
  bigint changed = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    const double id = (double) atom->tag[i];
    if (state[i][0] != 0.0 && state[i][0] != id) changed++;
    state[i][0] = id;
  }
  bigint changed_all = 0;
  MPI_Allreduce(&changed, &changed_all, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  return changed_all;
}
