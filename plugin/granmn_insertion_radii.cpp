/* ----------------------------------------------------------------------
   The radii pair_style gran/mn's cut-offs follow (granmn_insertion_radii.h).
------------------------------------------------------------------------- */

#include "granmn_insertion_radii.h"

#include "atom.h"
#include "fix.h"
#include "granmn_compat.h"

#include <vector>

using namespace LAMMPS_NS;

namespace granmn {

// The inserting fixes tell their largest radius through extract("radius"), as LAMMPS's
// granular pair styles ask them; every such fix counts, not the first one only.
void largest_radii(LAMMPS *lmp, double *max_radius)
{
  const Atom *atom = lmp->atom;
  std::vector<double> local_max(atom->ntypes + 1, 0.0);
  for (int i = 0; i < atom->nlocal; i++)
    local_max[atom->type[i]] = MAX(local_max[atom->type[i]], atom->radius[i]);
  std::vector<Fix *> inserting = fixes_by_style(lmp->modify, "^pour");
  for (Fix *fix : fixes_by_style(lmp->modify, "^deposit")) inserting.push_back(fix);
  for (Fix *fix : inserting)
    for (int type = 1; type <= atom->ntypes; type++) {
      int asked = type;    // extract() overwrites it with the dimension of what it returns
      const auto *inserted = static_cast<const double *>(fix->extract("radius", asked));
      if (inserted) local_max[type] = MAX(local_max[type], *inserted);
    }
  MPI_Allreduce(&local_max[1], &max_radius[1], atom->ntypes, MPI_DOUBLE, MPI_MAX, lmp->world);
}

}    // namespace granmn
