/* -*- c++ -*- ----------------------------------------------------------
   fix contacts/mn: per-contact counters for the gran/mn styles.
   pair_style gran/mn and fix wall/gran/mn report contacts to it; a run without
   this fix pays nothing for it.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_CONTACTS_MN_H
#define LMP_FIX_CONTACTS_MN_H

#include "atom.h"
#include "fix_per_atom_state.h"
#include "update.h"

#include <vector>

namespace LAMMPS_NS {

class FixContactsMN : public FixPerAtomState {
 public:
  // Columns of the per-atom array.
  enum { BEGUN_PARTICLE, BEGUN_BOUNDARY, TIME_PARTICLE, TIME_BOUNDARY, TIME_MULTIPLE, NOW, NCOLS };
  // Per-pair state the pair style keeps in its neighbor history for this fix.
  enum { PAIR_START, PAIR_VN_START, PAIR_PEAK, PAIR_STATE_SIZE };
  // Per atom, wall fix and wall side, kept by the wall fix: touching, start time, v_n at
  // start, peak overlap.
  enum { WALL_SLOTS = 4 };

  FixContactsMN(class LAMMPS *, int, char **);
  ~FixContactsMN() override;
  int setmask() override;
  void init() override;
  void setup_pre_force(int) override;
  void pre_force(int) override;
  void setup(int) override;
  void end_of_step() override;
  int modify_param(int, char **) override;
  double compute_vector(int) override;

  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;
  void grow_arrays(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // Called by pair_style gran/mn for a pair in contact at this force evaluation. `state`
  // is the pair's PAIR_STATE_SIZE history slots; `began` that the pair was not touching
  // before; `tally_j`: j's share is counted here (owned, or newton on).
  void pair_touching(int i, int j, bool j_is_boundary, bool i_is_boundary, double *state,
                     bool began, double delta, double vn, bool tally_j);
  // Called by pair_style gran/mn when a pair stops touching; `record`: this process
  // writes the contact's row (avoids duplicates of pairs stored on two processes).
  // i is the mobile atom when one of the two is a boundary element.
  void pair_ended(int i, int j, bool boundary, const double *state, double vn, bool record);
  // Called by fix wall/gran/mn for every atom of its group and wall side; w is that atom's
  // WALL_SLOTS for this wall fix and side.
  void wall_state(int i, double *w, bool touching, double delta, double vn);

 private:
  // state[i]: the NCOLS output columns
  double *step_particle, *step_boundary;    // contacts at this step, owned + ghost
  double *begun_particle, *begun_boundary;  // contacts begun at this step, owned + ghost
  int nmax_step;
  // The fix's own clock: the time of the current step, the sum of the time steps actually
  // taken (a timestep changed between runs counts from then on; LAMMPS's time restarts at
  // zero after read_restart in this version, this clock does not).
  double now;
  bigint clock_step;           // the step `now` belongs to
  double window_start;         // time at which accumulation (re)started
  int rows_every;              // local rows: contacts completed in the last N steps (0: none)
  std::vector<double> rows;    // 8 values per completed contact
  double **row_array;
  int nmax_rows;
  bigint rows_cleared;
  double vector_sums[8];
  bigint vector_step;

  void advance_clock();
  void add_row(double tag_i, double tag_j, double kind, double start_time, double vn_start,
               double vn_end, double peak);
  void collect(bool accumulate_time);
  void grow_step_arrays();
  void publish_rows();
};

// Inline: called for every contact (and every atom near a wall) at every step.
inline void FixContactsMN::pair_touching(int i, int j, bool j_is_boundary, bool i_is_boundary,
                                  double *state, bool began, double delta, double vn,
                                  bool tally_j)
{
  if (began) {
    state[PAIR_START] = now;
    state[PAIR_VN_START] = vn;
    state[PAIR_PEAK] = delta;
  } else if (delta > state[PAIR_PEAK]) {
    state[PAIR_PEAK] = delta;
  }
  (j_is_boundary ? step_boundary : step_particle)[i] += 1.0;
  if (began) (j_is_boundary ? begun_boundary : begun_particle)[i] += 1.0;
  if (tally_j) {
    (i_is_boundary ? step_boundary : step_particle)[j] += 1.0;
    if (began) (i_is_boundary ? begun_boundary : begun_particle)[j] += 1.0;
  }
}

inline void FixContactsMN::wall_state(int i, double *w, bool touching, double delta, double vn)
{
  if (touching) {
    if (w[0] == 0.0) {
      w[0] = 1.0;
      w[1] = now;
      w[2] = vn;
      w[3] = delta;
      // owned atom: counted directly, so that the order of fix setups does not matter
      if (atom->mask[i] & groupbit) state[i][BEGUN_BOUNDARY] += 1.0;
    } else if (delta > w[3]) {
      w[3] = delta;
    }
    step_boundary[i] += 1.0;
  } else if (w[0] != 0.0) {
    w[0] = 0.0;
    if (rows_every && (atom->mask[i] & groupbit)) add_row(atom->tag[i], 0, 2, w[1], w[2], vn, w[3]);
  }
}

}    // namespace LAMMPS_NS

#endif
