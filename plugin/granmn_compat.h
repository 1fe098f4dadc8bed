/* -*- c++ -*- ----------------------------------------------------------
   The LAMMPS API differences between the generations the plugin builds against, in one place,
   keyed on LAMMPS_VERSION_NUMBER (yyyymmdd of src/version.h; CMakeLists.txt defines it).
   Tested: 29 Sep 2021 (Debian 12) and 4 Feb 2025 (Debian trixie). The cut-offs are the
   releases that changed each API (doc/src/Developer_updating.rst of current LAMMPS).
------------------------------------------------------------------------- */

#ifndef GRANMN_COMPAT_H
#define GRANMN_COMPAT_H

#include "comm.h"
#include "neigh_request.h"
#include "neighbor.h"

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

}    // namespace granmn

// Pair::transfer_history gained the two atom types with the GranularModel refactor (early
// 2023); gran/mn does not need them. Used as `void GRANMN_TRANSFER_HISTORY(source, target)`.
#if LAMMPS_VERSION_NUMBER >= 20230208
#define GRANMN_TRANSFER_HISTORY(source, target) \
  transfer_history(double *source, double *target, int, int)
#else
#define GRANMN_TRANSFER_HISTORY(source, target) transfer_history(double *source, double *target)
#endif

#endif
