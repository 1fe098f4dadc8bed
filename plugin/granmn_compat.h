/* -*- c++ -*- ----------------------------------------------------------
   The LAMMPS API differences between the generations the plugin builds against, in one place,
   keyed on LAMMPS_VERSION_NUMBER (yyyymmdd of src/version.h; CMakeLists.txt defines it).
   Tested: 29 Sep 2021 (Debian 12), 4 Feb 2025 (Debian trixie) and 4 Jul 2026 (Debian sid).
   The cut-offs are the releases that changed each API (doc/src/Developer_updating.rst of
   current LAMMPS); where that names none, a release known to have the change or the first
   tested one, as said at each.
------------------------------------------------------------------------- */

#ifndef GRANMN_COMPAT_H
#define GRANMN_COMPAT_H

#include "comm.h"
#include "domain.h"
#include "fix.h"
#include "modify.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "region.h"
#include "utils.h"

#include <string>
#include <vector>

#ifndef LAMMPS_VERSION_NUMBER
#error "LAMMPS_VERSION_NUMBER (yyyymmdd) must be defined: CMakeLists.txt reads it from src/version.h"
#endif

namespace granmn {

// 24Mar2022: comm->reverse_comm_fix(this) became the overloaded comm->reverse_comm(this).
inline void reverse_comm(LAMMPS_NS::Comm *comm, LAMMPS_NS::Fix *fix)
{
#if LAMMPS_VERSION_NUMBER >= 20220324
  comm->reverse_comm(fix);
#else
  comm->reverse_comm_fix(fix);
#endif
}

// 24Mar2022: comm->forward_comm_pair(this) became the overloaded comm->forward_comm(this).
inline void forward_comm(LAMMPS_NS::Comm *comm, LAMMPS_NS::Pair *pair)
{
#if LAMMPS_VERSION_NUMBER >= 20220324
  comm->forward_comm(pair);
#else
  comm->forward_comm_pair(pair);
#endif
}

// 24Mar2022: a neighbor list is requested with flags instead of by editing the request.
// A size (finite-radius) half list, with per-pair history if asked.
inline void request_size_list(LAMMPS_NS::Neighbor *neighbor, LAMMPS_NS::Pair *pair,
                              int instance, bool history)
{
#if LAMMPS_VERSION_NUMBER >= 20220324
  (void) instance;
  neighbor->add_request(pair, LAMMPS_NS::NeighConst::REQ_SIZE |
                                  (history ? LAMMPS_NS::NeighConst::REQ_HISTORY : 0));
#else
  const int irequest = neighbor->request(pair, instance);
  neighbor->requests[irequest]->size = 1;
  if (history) neighbor->requests[irequest]->history = 1;
#endif
}

// Modify's fix look-ups: get_fix_by_id() and get_fix_by_style() (lammps/lammps PR #3001, late
// 2021; not in the 29 Sep 2021 stable line) replace find_fix(), deprecated in 4 Jul 2026's
// modify.h, and the arrays fix[]/nfix, which upstream means to make private (issue #2870).
// The cut-off errs late, at a later release that has them; the arrays serve every one before.
inline LAMMPS_NS::Fix *fix_by_id(LAMMPS_NS::Modify *modify, const std::string &id)
{
#if LAMMPS_VERSION_NUMBER >= 20220324
  return modify->get_fix_by_id(id);
#else
  const int ifix = modify->find_fix(id);
  return ifix >= 0 ? modify->fix[ifix] : nullptr;
#endif
}

// The fixes whose style matches a regex (utils::strmatch), in the order they were defined.
inline std::vector<LAMMPS_NS::Fix *> fixes_by_style(LAMMPS_NS::Modify *modify,
                                                    const std::string &style)
{
#if LAMMPS_VERSION_NUMBER >= 20220324
  return modify->get_fix_by_style(style);
#else
  std::vector<LAMMPS_NS::Fix *> matches;
  for (int k = 0; k < modify->nfix; k++)
    if (LAMMPS_NS::utils::strmatch(modify->fix[k]->style, style)) matches.push_back(modify->fix[k]);
  return matches;
#endif
}

// Every fix, in the order they were defined (get_fix_list() came with the look-ups above).
inline std::vector<LAMMPS_NS::Fix *> all_fixes(LAMMPS_NS::Modify *modify)
{
#if LAMMPS_VERSION_NUMBER >= 20220324
  return modify->get_fix_list();
#else
  return std::vector<LAMMPS_NS::Fix *>(modify->fix, modify->fix + modify->nfix);
#endif
}

// The region of an ID, nullptr if none: Domain::get_region_by_id where LAMMPS has it (it came
// with the regions' refactor of 2022, which took away find_region and the regions[] array),
// else find_region. Chosen by what Domain declares, not by a version number: the release that
// changed it is not among the tested ones.
template <typename D>
auto region_lookup(D *domain, const std::string &id, int) -> decltype(domain->get_region_by_id(id))
{
  return domain->get_region_by_id(id);
}
template <typename D> LAMMPS_NS::Region *region_lookup(D *domain, const std::string &id, long)
{
  const int index = domain->find_region(id);
  return index < 0 ? nullptr : domain->regions[index];
}
inline LAMMPS_NS::Region *region_by_id(LAMMPS_NS::Domain *domain, const std::string &id)
{
  return region_lookup(domain, id, 0);
}

// Member k of a union or intersect region: Region::reglist where LAMMPS has it (the regions'
// refactor of 2022), else its index into Domain::regions (Region::list). Chosen by what Region
// declares, as region_by_id.
template <typename R>
auto member_lookup(LAMMPS_NS::Domain *, R *region, int k, int) -> decltype(region->reglist[k])
{
  return region->reglist[k];
}
template <typename R>
LAMMPS_NS::Region *member_lookup(LAMMPS_NS::Domain *domain, R *region, int k, long)
{
  return domain->regions[region->list[k]];
}
inline LAMMPS_NS::Region *region_member(LAMMPS_NS::Domain *domain, LAMMPS_NS::Region *region,
                                        int k)
{
  return member_lookup(domain, region, k, 0);
}

}    // namespace granmn

// Pair::transfer_history gained the two atom types with the GranularModel refactor (early
// 2023); gran/mn does not need them. Used as `void GRANMN_TRANSFER_HISTORY(source, target)`.
#if LAMMPS_VERSION_NUMBER >= 20230208
#define GRANMN_TRANSFER_HISTORY(source, target) \
  transfer_history(double *source, double *target, int, int)
#else
#define GRANMN_TRANSFER_HISTORY(source, target) transfer_history(double *source, double *target)
#endif

// Pair::atom2cut() and Pair::radii2cut(), through which a finite-size pair style gave neighbor
// multi its cutoffs, are gone by 4 Jul 2026 (dropped after 4 Feb 2025): LAMMPS takes 2 r and
// r_i + r_j itself, the values gran/mn returned. The cut-off is the first tested release
// without them.
#if LAMMPS_VERSION_NUMBER < 20260704
#define GRANMN_PAIR_HAS_ATOM2CUT 1
#endif

#endif
