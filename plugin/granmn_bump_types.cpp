/* ----------------------------------------------------------------------
   pair_style gran/mn's bump types (granmn_bump_types.h).
------------------------------------------------------------------------- */

#include "granmn_bump_types.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "granmn_compat.h"
#include "modify.h"
#include "neighbor.h"
#include "utils.h"

#include <cstring>
#include <functional>
#include <string>

using namespace LAMMPS_NS;

namespace granmn {

int BumpTypes::parse(LAMMPS *lmp, int narg, char **arg, int iarg)
{
  if (strcmp(arg[iarg], "wall_types") != 0) return 0;
  const int first = iarg++;
  while (iarg < narg && utils::is_integer(arg[iarg]))
    types.push_back(utils::inumeric(FLERR, arg[iarg++], false, lmp));
  if (types.empty())
    lmp->error->all(FLERR, "Illegal pair_style gran/mn command: wall_types needs atom types");
  return iarg - first;
}

void BumpTypes::check_types(LAMMPS *lmp)
{
  const int ntypes = lmp->atom->ntypes;
  marked.assign(ntypes + 1, 0);
  for (int t : types) {
    if (t < 1 || t > ntypes)
      lmp->error->all(FLERR, "pair_style gran/mn: wall type {} is out of range 1..{}", t, ntypes);
    marked[t] = 1;
  }
}

// The boundary rule holds for immobile bumps: a bump that moves would collide with e and
// tau of neither a pair nor the boundary. A bump of diameter 0 would have its centre inside
// the disk at the first touch.
void BumpTypes::check_atoms(LAMMPS *lmp) const
{
  if (types.empty()) return;
  Atom *atom = lmp->atom;
  const int *type = atom->type, *mask = atom->mask;
  // how many bumps, over all ranks, satisfy `test`
  auto count_bumps = [&](const std::function<bool(int)> &test) {
    bigint mine = 0, all = 0;
    for (int i = 0; i < atom->nlocal; i++)
      if (is_bump(type[i]) && test(i)) mine++;
    MPI_Allreduce(&mine, &all, 1, MPI_LMP_BIGINT, MPI_SUM, lmp->world);
    return all;
  };
  const bigint points_all = count_bumps([&](int i) { return atom->radius[i] == 0.0; });
  if (points_all)
    lmp->error->all(FLERR, "pair_style gran/mn: {} atoms of wall_types have diameter 0: a bump "
                           "is a fixed {} with a radius (a disk would touch its centre at once); "
                           "set their diameter",
                    points_all, lmp->domain->dimension == 3 ? "sphere" : "disk");
  for (const Fix *fix : all_fixes(lmp->modify)) {
    if (!fix->time_integrate) continue;
    const bigint integrated_all =
        count_bumps([&](int i) { return (mask[i] & fix->groupbit) != 0; });
    if (integrated_all)
      lmp->error->all(FLERR, "pair_style gran/mn: fix {} ({}) integrates {} atoms of "
                             "wall_types, which are immobile bumps with the boundary rule: "
                             "leave them out of its group",
                      fix->id, fix->style, integrated_all);
  }
}

// Two immobile boundary elements never interact.
void BumpTypes::exclude_bump_pairs(LAMMPS *lmp)
{
  std::vector<std::pair<int, int>> wanted;
  for (size_t a = 0; a < types.size(); a++)
    for (size_t b = a; b < types.size(); b++) wanted.emplace_back(types[a], types[b]);
  if (wanted == excluded) return;
  release_exclusions(lmp);
  for (const auto &pair : wanted) {
    std::string ti = std::to_string(pair.first), tj = std::to_string(pair.second);
    char *words[4] = {(char *) "exclude", (char *) "type", &ti[0], &tj[0]};
    lmp->neighbor->modify_params(4, words);
  }
  excluded = wanted;
}

void BumpTypes::release_exclusions(LAMMPS *lmp)
{
  Neighbor *neighbor = lmp->neighbor;
  for (const auto &pair : excluded)
    for (int k = 0; k < neighbor->nex_type; k++)
      if (neighbor->ex1_type[k] == pair.first && neighbor->ex2_type[k] == pair.second) {
        for (int m = k + 1; m < neighbor->nex_type; m++) {
          neighbor->ex1_type[m - 1] = neighbor->ex1_type[m];
          neighbor->ex2_type[m - 1] = neighbor->ex2_type[m];
        }
        neighbor->nex_type--;
        break;
      }
  excluded.clear();
}

}    // namespace granmn
