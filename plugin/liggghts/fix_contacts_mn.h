/* LIGGGHTS 3.8 fix contacts/mn: the contact counters of the study (docs/liggghts.md), as the
   LAMMPS plugin's fix contacts/mn counts them, for the contacts that `model mn` computes
   (pair style and walls): per atom of the group, contacts begun with other particles and with
   the boundary (walls, particles in fix freeze's group), the time touching at least one other
   particle, the time touching the boundary, the time with two or more contacts, and the
   contacts now; a global vector of their sums over the group, the contacts now and the
   window's length, since the fix was defined or `fix_modify ID reset`. The plugin's fix's
   columns (mn_output_schema.h), so that the decks write the same files. No per-contact rows.
     fix ID group-ID contacts/mn */
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
  void end_of_step();
  double compute_vector(int);
  int modify_param(int, char **);

 private:
  void clear_tallies();
  void reset_window();

  class FixPropertyAtom *accumulated;    // per atom: the six columns, migrating with the atom
  std::vector<double> particle, boundary, begun_particle, begun_boundary;
  double window;                         // time since the window began
};

}    // namespace LAMMPS_NS

#endif
#endif
