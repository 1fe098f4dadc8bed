/* LIGGGHTS 3.8 fix contacts/mn: the contact counters of the study (docs/liggghts.md), as the
   LAMMPS plugin's fix contacts/mn counts them, for the contacts that `model mn` computes
   (pair style and walls): per atom of the group, contacts begun with other particles and with
   the boundary (walls, particles in fix freeze's group), the time touching at least one other
   particle, the time touching the boundary, the time with two or more contacts, and the
   contacts now; a global vector of their sums over the group, the window's length, since the
   fix was defined or `fix_modify ID reset`, and the group's size. With `energy yes`, where the
   contacts' energy went (mn_energy.h; the pair style's models need `energy on`): per atom
   after the counters and summed in the global vector after the group's size, dissipated in
   the normal force, the tangential force while sticking and while sliding, and stored in the
   springs, then the work in flight (0: velocity Verlet). The plugin's fix's columns
   (mn_output_schema.h), so that the decks write the same files. No per-contact rows.
     fix ID group-ID contacts/mn [energy yes|no] */
#ifdef FIX_CLASS
FixStyle(contacts/mn,FixContactsMN)
#else
#ifndef LMP_FIX_CONTACTS_MN_H
#define LMP_FIX_CONTACTS_MN_H

#include <vector>

#include "fix.h"
#include "mn_contact_events.h"

namespace LAMMPS_NS {

class FixContactsMN : public Fix, public granmn::ContactCounter {
 public:
  FixContactsMN(class LAMMPS *, int, char **);
  void post_create();
  int setmask();
  void init();
  void setup_pre_force(int);
  void pre_force(int);
  void setup(int);
  void end_of_step();
  double compute_vector(int);
  int modify_param(int, char **);

 private:
  void clear_tallies();
  void absorb_energies();
  void reset_window();

  // With energy yes the per-atom columns go on with the energies (granmn::output::EnergySum),
  // then what they are made of: the atom's share of its contacts' energy taken (normal,
  // tangential) and lost while sliding since the fix was defined (fix_modify reset leaves
  // them, as the plugin's fix does), and stored in their springs at the last evaluation.
  enum { TAKEN_NORMAL = granmn::output::COUNTERS + granmn::output::ENERGY_SUMS,
         TAKEN_TANGENTIAL, SLID, STORED_NORMAL, STORED_TANGENTIAL, COLUMNS_WITH_ENERGY };
  bool energy;                           // energy yes
  int columns;                           // of the per-atom property
  class FixPropertyAtom *accumulated;    // per atom: the columns, migrating with the atom
  std::vector<double> particle, boundary, begun_particle, begun_boundary, energies;
  double window;                         // time since the window began
};

}    // namespace LAMMPS_NS

#endif
#endif
