// What the styles write and publish, by name and position: the columns of fix contacts/mn's
// counters and of its contact rows, the codes of a row's kind, and the variables the law's
// styles publish. The LAMMPS and LIGGGHTS styles take positions from here, `mn-law --columns`
// prints the names (for the post-processing, postprocess/output_schema.txt, and the tests that
// check the decks' titles against them). Free of any host.
#ifndef MN_OUTPUT_SCHEMA_H
#define MN_OUTPUT_SCHEMA_H

#include "mn_integration.h"

namespace granmn {
namespace output {

// fix contacts/mn's per-atom columns (f_c[1] ... of a dump), and the first entries of its
// global vector, their sums over the group. A "disk" is a flowing particle (a disc in 2D, a
// sphere in 3D); contacts_now is a count at one moment, the others grow over the window.
enum Counter { BEGUN_PARTICLE, BEGUN_BOUNDARY, TIME_PARTICLE, TIME_BOUNDARY, TIME_MULTIPLE, NOW,
               COUNTERS };
constexpr const char *COUNTER_NAMES[COUNTERS] = {"begun_disk", "begun_boundary", "time_disk",
                                                 "time_boundary", "time_multiple",
                                                 "contacts_now"};

// The global vector's entries after the sums: the window's length and the group's size.
enum VectorExtra { WINDOW = COUNTERS, GROUP_SIZE, VECTOR_SIZE };
constexpr const char *EXTRA_NAMES[VECTOR_SIZE - COUNTERS] = {"window", "group_size"};

// The columns of a completed contact's row (fix contacts/mn local N, for dump local).
enum RowColumn { ROW_ID_I, ROW_ID_J, ROW_KIND, ROW_START, ROW_DURATION, ROW_VN_START,
                 ROW_VN_END, ROW_PEAK, ROW_COLUMNS };
constexpr const char *ROW_NAMES[ROW_COLUMNS] = {"id_i", "id_j", "kind", "start", "duration",
                                                "vn_start", "vn_end", "peak"};

// With `energy yes` (fix contacts/mn): where the contacts' energy went (mn_energy.h,
// docs/model.md section 9), per atom after the counters (each contact's half to each of its
// disks, all of it to the disk against a bump) and summed in the global vector after its
// extras: dissipated in the normal force, in the tangential force while sticking and while
// sliding, and stored in the springs now. The global vector goes on with the work in flight,
// which an Adams-Bashforth 2 run's budget counts (mn::work_in_flight; 0 under velocity Verlet),
// and ends with the work the moving walls have done on the group's atoms since the fix was
// defined (mn::WallWork; 0 where no wall moves), which the budget counts as work done on the
// system.
enum EnergySum { DISSIPATED_NORMAL, DISSIPATED_STICKING, DISSIPATED_SLIDING, STORED,
                 ENERGY_SUMS };
constexpr const char *ENERGY_NAMES[ENERGY_SUMS] = {"dissipated_normal", "dissipated_sticking",
                                                   "dissipated_sliding", "stored"};
constexpr int VECTOR_SIZE_WITH_ENERGY = VECTOR_SIZE + ENERGY_SUMS + 2;
constexpr const char *IN_FLIGHT_NAME = "work_in_flight";
constexpr const char *WALL_WORK_NAME = "work_of_walls";

// A row's columns after ROW_COLUMNS with `energy yes`: what the contact dissipated in all, and
// of it while sliding.
enum RowEnergyColumn { ROW_DISSIPATED = ROW_COLUMNS, ROW_DISSIPATED_SLIDING,
                       ROW_COLUMNS_WITH_ENERGY };
constexpr const char *ROW_ENERGY_NAMES[ROW_COLUMNS_WITH_ENERGY - ROW_COLUMNS] = {
    "dissipated", "dissipated_sliding"};

// The codes of a row's kind column: between two disks, of a disk with the boundary.
enum ContactKind { KIND_DISKS = 1, KIND_BOUNDARY = 2 };
struct KindName {
  ContactKind code;
  const char *name;
};
constexpr KindName KINDS[] = {{KIND_DISKS, "disk"}, {KIND_BOUNDARY, "boundary"}};

// The law's derived values under the names the styles publish them as equal-style variables
// (a deck's `timestep $(v_mn_tau_c/100)`), in this order.
enum Published { PUBLISHED_TAU_C, PUBLISHED_TAU_W, PUBLISHED_E_W, PUBLISHED_ETA_N, PUBLISHED_KT,
                 PUBLISHED_ETA_T, PUBLISHED_DT_MAX_VERLET, PUBLISHED_DT_MAX_AB2, PUBLISHED };
constexpr const char *PUBLISHED_NAMES[PUBLISHED] = {
    "mn_tau_c", "mn_tau_w", "mn_e_w", "mn_eta_n", "mn_kt", "mn_eta_t", "mn_dt_max_verlet",
    "mn_dt_max_ab2"};
constexpr const char *PUBLISHED_PREFIX = "mn_";

// publish(name, value) for each published value of the law.
template <class Publish> void for_each_published(const mn::Law &law, Publish &&publish)
{
  double value[PUBLISHED];
  value[PUBLISHED_TAU_C] = law.tau_c;
  value[PUBLISHED_TAU_W] = law.tau_w;
  value[PUBLISHED_E_W] = law.e_w;
  value[PUBLISHED_ETA_N] = law.eta_n;
  value[PUBLISHED_KT] = law.kt;
  value[PUBLISHED_ETA_T] = law.eta_t;
  value[PUBLISHED_DT_MAX_VERLET] = mn::max_stable_dt(law, mn::Integrator::VelocityVerlet);
  value[PUBLISHED_DT_MAX_AB2] = mn::max_stable_dt(law, mn::Integrator::AdamsBashforth2);
  for (int k = 0; k < PUBLISHED; k++) publish(PUBLISHED_NAMES[k], value[k]);
}

}    // namespace output
}    // namespace granmn

#endif
