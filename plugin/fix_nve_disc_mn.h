/* -*- c++ -*- ----------------------------------------------------------
   fix nve/disc/mn: one pass per half step over the disks of a 2D scene, for x, y and omega_z
   only, under velocity Verlet (as fix nve/sphere disc) or the paper's Adams-Bashforth 2
   (Mitarai & Nakanishi 2003), with an optional uniform body force (gravity) in the same pass.
   fix nve/ab2 is this fix with scheme ab2 and no gravity.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_NVE_DISC_MN_H
#define LMP_FIX_NVE_DISC_MN_H

#include "fix_per_atom_state.h"

#include "mn_integration.h"

#include <cstddef>
#include <vector>

namespace LAMMPS_NS {

class FixNVEDiscMN : public FixPerAtomState {
 public:
  FixNVEDiscMN(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;
  void final_integrate() override;
  void post_run() override;
  void reset_dt() override;
  double memory_usage() override;

  // Its scheme and neigh_check, for the styles' run checks (granmn_run_checks.h names them).
  void *extract(const char *, int &) override;

  // One atom of the group, in the order of the passes, with its factors (the member `members`
  // below says what they are).
  struct Member {
    std::ptrdiff_t row;    // its rows' start in the flat per-atom arrays (granmn_flat_arrays.h)
    int atom;              // its local index
    double per_mass, per_inertia, weight_x, weight_y;
  };

 private:
  // Adams-Bashforth 2, per atom: the accelerations of the previous step (a_x, a_y, alpha_z),
  // and 1 once they exist.
  enum { AX, AY, ALPHA, HAS_PREVIOUS, NSTATE };
  // The group's local atoms in index order, each with its factors from its mass and radius,
  // listed again only when they may have changed (a run's setup, a new dt, atoms re-sorted at a
  // neighbour-list build, the first step after another run (run ... pre no skips the setup: a
  // set command may have come between), a fix adapt in the run):
  // velocity Verlet: dt/2 / m and dt/2 / (m r^2/2) (times ftm2v), as fix nve/sphere disc;
  // Adams-Bashforth 2: 1/m and 1/(m r^2/2) (times ftm2v); and the body force m g.
  // The passes read the list in order, one entry a disk, with no test of each atom's mask, whose
  // branch a group of disks among bumps (the collisional scene, its atoms sorted in space)
  // mispredicts at every other atom, and no per-atom array of factors to index. The group is not
  // dynamic (LAMMPS refuses a dynamic group for a fix that does not allow one).
  std::vector<Member> members;
  mn::Integrator integrator;
  bool has_gravity;
  double gravity[2];          // the acceleration, as fix gravity's vector style makes it
  double dtv, dtf;
  bool factors_every_step;    // a fix adapt may change masses or radii at any step
  bool factors_stale;         // a run ended since they were computed
  bigint factors_lastcall;    // the neighbour-list build the factors were computed after
  // m g is added to f after every other force, as by a fix gravity defined last: at each step
  // in the final pass, at a run's setup in this fix's setup if no fix defined after it adds
  // forces there (post-force fixes), else at the first step, before its kick
  bool gravity_at_setup;
  bool gravity_pending;       // not yet in this run's setup forces
  // neigh_check yes: LAMMPS's decision for a neighbour-list build (Neighbor::decide: every,
  // delay, check yes/no; with check yes, has a disk moved more than half the skin since the
  // last build) taken in this fix's pass over the disks, which asks LAMMPS for the build
  // (next_reneighbor); with neigh_modify once yes LAMMPS does not decide again
  bool neigh_check;
  double trigger_sq;          // (skin/2)^2, as LAMMPS computes it
  // x, y of each local atom at the last build, at x's row stride (3): a disk's test takes
  // its row offset from its member entry
  std::vector<double> held;
  bigint held_lastcall;

  void hold_positions();
  int build_due() const;
  void request_build(bool moved, int ago);

  void compute_factors();
  void refresh_factors();
  void add_gravity();
  void check_other_fixes();
};

}    // namespace LAMMPS_NS

#endif
