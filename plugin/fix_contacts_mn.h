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
  // What this fix keeps per contact, wherever the contact lives: in the pair style's neighbor
  // history (RECORD_SIZE values) or in a wall fix's per-atom state (WALL_SLOTS per side: the
  // record, then whether the atom touches that wall).
  enum { RECORD_START, RECORD_VN_START, RECORD_PEAK, RECORD_SIZE };
  enum { WALL_TOUCHING = RECORD_SIZE, WALL_SLOTS };

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

  // The contact events, one path for pairs and walls. A contact's record lives with the
  // contact (see RECORD_*); the style that owns it reports:
  //   touching(record, began, ...)  at every force evaluation while in contact,
  //   ended(record, ...)            at the first one after it ends (its row, if asked).
  // pair_style gran/mn: a pair in contact; `tally_j`: j's share is counted here (owned, or
  // newton on).
  void pair_touching(int i, int j, bool j_is_boundary, bool i_is_boundary, double *record,
                     bool began, double delta, double vn, bool tally_j);
  // pair_style gran/mn: a pair stopped touching; `write_row`: this process writes its row
  // (a pair stored on two processes has one row). i is the mobile atom against a bump.
  void pair_ended(int i, int j, bool boundary, const double *record, double vn, bool write_row);
  // fix wall/gran/mn, for every atom of its group and wall side; `w` is that atom's
  // WALL_SLOTS for the wall fix and side.
  void wall_state(int i, double *w, bool touching, double delta, double vn);

 private:
  // state[i]: the NCOLS output columns
  double *step_particle, *step_boundary;    // contacts at this step, owned + ghost
  double *begun_particle, *begun_boundary;  // contacts begun at this step, owned + ghost
  int nmax_step;
  // One process: a ghost's tallies go straight to the disk it images (atom->map), so nothing
  // is exchanged; only the disks in contact are visited: `touched` lists those of this step
  // (tallied, then zeroed by collect), `touched_before` those of the last step (their NOW is
  // zeroed first). The work per step scales with the disks in contact, not with all disks.
  // Else the tallies travel by reverse communication and every disk is visited.
  bool fold_ghosts;
  std::vector<int> touched, touched_before;
  // The fix's own clock: the time of the current step, the sum of the time steps actually
  // taken (a timestep changed between runs counts from then on; LAMMPS's time restarts at
  // zero after read_restart in this version, this clock does not).
  double now;
  bigint clock_step;           // the step `now` belongs to
  double window_start;         // time at which accumulation (re)started
  int rows_every;              // local rows: contacts completed in the last N steps (0: none)
  std::vector<double> rows;    // 8 values per completed contact, not yet dumped
  double **row_array;
  int nmax_rows;
  // The first rows_handed rows were handed to dump local at step handed_step (a multiple of N);
  // they go at the next step, whatever its number (reset_timestep may move it either way).
  int rows_handed;
  bigint handed_step;
  double vector_sums[8];
  bigint vector_step;

  void advance_clock();
  void drop_handed_rows();
  void touching(double *record, bool began, double delta, double vn);
  void tally(int i, bool boundary, bool began);
  void ended(const double *record, double tag_i, double tag_j, double kind, double vn_end);
  void collect(bool accumulate_time);
  void grow_step_arrays();
  void publish_rows();
};

// Inline: called for every contact (and every atom near a wall) at every step.
inline void FixContactsMN::touching(double *record, bool began, double delta, double vn)
{
  if (began) {
    record[RECORD_START] = now;
    record[RECORD_VN_START] = vn;
    record[RECORD_PEAK] = delta;
  } else if (delta > record[RECORD_PEAK]) {
    record[RECORD_PEAK] = delta;
  }
}

// One contact of atom i at this step (with a boundary or not; begun at this step or not).
inline void FixContactsMN::tally(int i, bool boundary, bool began)
{
  if (step_particle[i] == 0.0 && step_boundary[i] == 0.0) touched.push_back(i);
  (boundary ? step_boundary : step_particle)[i] += 1.0;
  if (began) (boundary ? begun_boundary : begun_particle)[i] += 1.0;
}

inline void FixContactsMN::pair_touching(int i, int j, bool j_is_boundary, bool i_is_boundary,
                                         double *record, bool began, double delta, double vn,
                                         bool tally_j)
{
  touching(record, began, delta, vn);
  tally(i, j_is_boundary, began);
  if (tally_j) {
    if (fold_ghosts && j >= atom->nlocal) j = atom->map(atom->tag[j]);
    tally(j, i_is_boundary, began);
  }
}

inline void FixContactsMN::wall_state(int i, double *w, bool in_contact, double delta, double vn)
{
  if (in_contact) {
    const bool began = w[WALL_TOUCHING] == 0.0;
    touching(w, began, delta, vn);
    w[WALL_TOUCHING] = 1.0;
    // owned atom: counted directly, so that the order of fix setups does not matter
    if (began && (atom->mask[i] & groupbit)) state[i][BEGUN_BOUNDARY] += 1.0;
    tally(i, true, false);
  } else if (w[WALL_TOUCHING] != 0.0) {
    w[WALL_TOUCHING] = 0.0;
    if (atom->mask[i] & groupbit) ended(w, atom->tag[i], 0, 2, vn);
  }
}

}    // namespace LAMMPS_NS

#endif
