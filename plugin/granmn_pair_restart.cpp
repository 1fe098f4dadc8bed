/* ----------------------------------------------------------------------
   pair_style gran/mn's settings in restart files (granmn_pair_restart.h).
------------------------------------------------------------------------- */

#include "granmn_pair_restart.h"

#include "comm.h"
#include "utils.h"

using namespace LAMMPS_NS;

namespace granmn {

// kn, e, beta, mu; limit_damping, coulomb_cutback, the number of bump types, the history's
// size; the bump types.
void write_pair_settings(FILE *fp, const PairSettings &settings)
{
  const mn::Material &m = settings.material;
  const double values[4] = {m.kn, m.e, m.beta, m.mu};
  fwrite(values, sizeof(double), 4, fp);
  const int flags[4] = {settings.options.limit_damping, settings.options.coulomb_cutback,
                        (int) settings.bump_types.size(), settings.history_size};
  fwrite(flags, sizeof(int), 4, fp);
  if (!settings.bump_types.empty())
    fwrite(settings.bump_types.data(), sizeof(int), settings.bump_types.size(), fp);
}

PairSettings read_pair_settings(LAMMPS *lmp, FILE *fp)
{
  const int me = lmp->comm->me;
  MPI_Comm world = lmp->world;
  double values[4];
  int flags[4];
  if (me == 0) {
    utils::sfread(FLERR, values, sizeof(double), 4, fp, nullptr, lmp->error);
    utils::sfread(FLERR, flags, sizeof(int), 4, fp, nullptr, lmp->error);
  }
  MPI_Bcast(values, 4, MPI_DOUBLE, 0, world);
  MPI_Bcast(flags, 4, MPI_INT, 0, world);
  PairSettings settings;
  settings.material = {values[0], values[1], values[2], values[3]};
  settings.options.limit_damping = flags[0];
  settings.options.coulomb_cutback = flags[1];
  settings.bump_types.resize(flags[2]);
  settings.history_size = flags[3];
  if (me == 0 && flags[2] > 0)
    utils::sfread(FLERR, settings.bump_types.data(), sizeof(int), flags[2], fp, nullptr,
                  lmp->error);
  if (flags[2] > 0) MPI_Bcast(settings.bump_types.data(), flags[2], MPI_INT, 0, world);
  return settings;
}

}    // namespace granmn
