/* -*- c++ -*- ----------------------------------------------------------
   pair_style gran/mn: the Mitarai-Nakanishi 2D linear spring-dashpot law (and its 3D form for
   spheres in dimension 3).
   The LAMMPS side of the law: the force loop and its neighbour history; the law itself is in
   mn_contact.h, the style's other jobs in the granmn_*.h units it names.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_GRAN_MN_H
#define LMP_PAIR_GRAN_MN_H

#include "granmn_bump_types.h"
#include "granmn_compat.h"
#include "granmn_contact_storage.h"
#include "pair.h"

#include "mn_contact.h"
#include "mn_contact_events.h"

namespace LAMMPS_NS {

class PairGranMN : public Pair {
 public:
  PairGranMN(class LAMMPS *);
  ~PairGranMN() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  void setup() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  double single(int, int, int, int, double, double, double, double &) override;
  // The law as derived for the current settings (granmn::LAW_EXTRACT_NAME): the wall fix takes
  // it from here.
  void *extract(const char *, int &) override;
  // The ghosts' velocity and spin, which the law reads, when LAMMPS does not send them
  // (comm_modify vel no in 2D): what compute() sends them with.
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  void GRANMN_TRANSFER_HISTORY(, ) override;
#ifdef GRANMN_PAIR_HAS_ATOM2CUT
  double atom2cut(int) override;
  double radii2cut(double, double) override;
#endif

 private:
  mn::Law law;
  granmn::BumpTypes bumps;           // the wall_types: immobile boundary elements
  granmn::ContactLayout layout;      // of a contact's neighbor history (none: size 0)
  mn::Integrator integrator = mn::Integrator::VelocityVerlet;    // the run's, found at init_style
  int restart_history_size;          // per-pair history size in the restart read, -1 if none
  granmn::ContactObserver *observer;    // nullptr unless fix contacts/mn is defined
  bool law_reported;
  // comm_modify vel no in 2D: this style sends the ghosts' vx, vy and omega_z itself at each
  // compute (comm_forward values an atom)
  bool sends_ghost_velocity = false;
  double force_per_mass_acceleration;    // 1/ftm2v: mass x acceleration in force units
  double *max_radius;                // per type, for the cutoffs

  class FixDummy *fix_dummy;
  class FixNeighHistory *fix_history;

  void allocate();
  void publish_law();
  void follow_dimension();
  void set_ghost_velocity();
  void set_up_history();
  template <int DIM> void report_end(int, int, const double *, double, const double *,
                                     const tagint *, const mn::ContactEnergy *);
  template <int DIM> void compute_for(bool friction, bool observed, bool energy);
  struct LoopData;
  template <int DIM, bool FRICTION, bool OBSERVED, bool ENERGY> void compute_loop();
  // called from compute_loop only: hidden, so that the call is direct, not through the PLT
  template <int DIM, bool FRICTION, bool OBSERVED, bool ENERGY>
  __attribute__((noinline, visibility("hidden"))) void
  touching_pair(const LoopData &, int, int, double, double, double, double, double, int *,
                double *);
  template <int DIM, bool OBSERVED, bool ENERGY>
  __attribute__((noinline, visibility("hidden"))) void
  ended_pair(const LoopData &, int, int, double, double, double, double, int *, double *, int,
             int);
  template <int DIM> double single_contact(int, int, double, double &);
  template <int DIM>
  mn::ContactEnergy book_ended(const LoopData &, int, int, const double *, double, double *);
};

}    // namespace LAMMPS_NS

#endif
