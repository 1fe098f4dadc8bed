/* LIGGGHTS 3.8 tangential model `mn`: the tangential force of the Mitarai-Nakanishi law, with
   normal model `mn` (docs/liggghts.md). The force is mn_contact.h's, as in the LAMMPS pair style
   gran/mn: the trial force -2M (k_t u_t + eta_t v_t), capped at mu |fn|, with u_t the integral
   of v_t over the contact (3 history values; in 2D the first holds the scalar u_t along t).
   Settings: coulomb_cutback on|off (off: the paper's literal u_t; on: u_t cut back to the
   Coulomb limit while sliding); energy on|off (off; pair_style gran only: each contact keeps
   the energy history that fix contacts/mn energy yes books, mn_energy.h). It keeps the
   contact's history, and so tells when a contact begins: u_t starts from zero there, and with a
   fix contacts/mn defined it adds each touching contact to the fix's tallies at every
   evaluation, those begun counted as such, and with energy yes its energies, and those of each
   contact that has just ended. */
#ifdef TANGENTIAL_MODEL
TANGENTIAL_MODEL(TANGENTIAL_MN,mn,20)
#else
#ifndef TANGENTIAL_MODEL_MN_H_
#define TANGENTIAL_MODEL_MN_H_
#include <cmath>
#include <string>

#include "atom.h"
#include "contact_models.h"
#include "domain.h"
#include "fix_contact_history.h"
#include "granmn_liggghts_law.h"
#include "mn_energy.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "tangential_model_base.h"
#include "update.h"

namespace LIGGGHTS {
namespace ContactModels {

template <>
class TangentialModel<TANGENTIAL_MN> : public TangentialModelBase {
 public:
  TangentialModel(LAMMPS *lmp, IContactHistorySetup *hsetup, class ContactModelBase *c)
      : TangentialModelBase(lmp, hsetup, c)
  {
    // the pass that last found the contact touching (begins): the same seen from j
    seen_offset = hsetup->add_history_value("mn_seen", "0");
    // u_t is i's displacement relative to j: seen from j it changes sign (newton flag 1)
    ut_offset = hsetup->add_history_value("mn_ut_x", "1");
    hsetup->add_history_value("mn_ut_y", "1");
    hsetup->add_history_value("mn_ut_z", "1");
  }

  void registerSettings(Settings &settings)
  {
    settings.registerOnOff("coulomb_cutback", law.options.coulomb_cutback, false);
    settings.registerOnOff("energy", keeps_energy, false);
  }

  // energy on: the energy history of velocity Verlet (LIGGGHTS's nve/sphere) in this dimension,
  // after u_t. Its last force's normal, and in 3D its tangential force, change sign seen from j
  // (newton flag 1); f_n (and in 2D f_t, along t, which turns with n) and the energies do not.
  void postSettings(IContactHistorySetup *hsetup, ContactModelBase *models)
  {
    wall = models->is_wall();
    if (!keeps_energy || wall) return;
    dimension = domain->dimension;
    const int size = mn::energy_history_size(mn::Integrator::VelocityVerlet, dimension);
    for (int s = 0; s < size; s++) {
      const int p = s - mn::ENERGY_PREVIOUS_FORCE;
      const bool flips = p >= 0 && (p < dimension || (dimension == 3 && p >= 4));
      const int offset =
          hsetup->add_history_value("mn_energy_" + std::to_string(s), flips ? "1" : "0");
      if (s == 0) energy_offset = offset;
    }
  }

  void connectToProperties(PropertyRegistry &registry)
  {
    law.connect(lmp, registry, "tangential mn");
    counter = granmn_liggghts::find_counter(lmp);
    energies = counter ? counter->energy_tallies() : nullptr;
    if (energies && wall)
      error->all(FLERR, "fix contacts/mn energy yes: fix wall/gran with model mn cannot book its "
                        "contacts' energies (LIGGGHTS clears a wall contact's history at the first "
                        "evaluation that finds the particle apart, before the contact's last "
                        "force could be booked): use energy no, or the LAMMPS plugin's fix "
                        "wall/gran/mn");
    if (energies && !wall && !atom->map_style)
      error->all(FLERR, "fix contacts/mn energy yes needs an atom map (atom_modify map array): "
                        "a contact that ends where the neighbour lists are built is found by "
                        "its partner's ID");
    if (energies && energy_offset < 0)
      error->all(FLERR, "fix contacts/mn energy yes: pair_style gran keeps no energy history "
                        "per contact: add energy on after its models (pair_style gran model mn "
                        "tangential mn energy on)");
  }

  GRANMN_CONTACT_WORK void surfacesIntersect(const SurfacesIntersectData &sidata,
                                             ForceData &i_forces, ForceData &j_forces)
  {
    if (sidata.contact_flags) *sidata.contact_flags |= CONTACT_TANGENTIAL_MODEL;
    const mn::Law &pair_law = law.laws(sidata.itype, sidata.jtype);
    const double scale =
        granmn_liggghts::mass_scale(sidata) * law.laws.force_per_mass_acceleration;
    double *ut = &sidata.contact_history[ut_offset];
    const bool began = begins(sidata.contact_history[seen_offset]);
    if (began)
      for (int c = 0; c < 3; c++) ut[c] = 0.0;
    if (counter) count(sidata, began);
    // LIGGGHTS re-evaluates forces without a step (setup) with shearupdate 0: u_t stays
    const double dt_history = sidata.computeflag && sidata.shearupdate ? update->dt : 0.0;
    const double ut_before = energies ? ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2] : 0.0;

    double ft[3], torque_i[3] = {0.0, 0.0, 0.0}, torque_j[3] = {0.0, 0.0, 0.0};
    if (law.two_d) {
      // the kinematics model mn computed (granmn_liggghts::keep)
      const mn::Kinematics k = granmn_liggghts::kept2(sidata);
      mn::Force f = mn::tangential_force(pair_law, scale, k, sidata.Fn, ut, dt_history,
                                         mn::Integrator::VelocityVerlet, nullptr);
      if (energies) book_energy(sidata, pair_law, scale, k, f, ut_before, dt_history, began);
      f.fn = 0.0;    // the normal model has applied it
      const mn::Cartesian fxy = mn::cartesian(k, f);
      ft[0] = fxy.fx;
      ft[1] = fxy.fy;
      ft[2] = 0.0;
      torque_i[2] = mn::torque(f, sidata.radi);
      if (!sidata.is_wall) torque_j[2] = mn::torque(f, sidata.radj);
    } else {
      const mn::Kinematics3 k = granmn_liggghts::kept3(sidata);
      const mn::Force3 f = mn::tangential_force3(pair_law, scale, k, sidata.Fn, ut, dt_history);
      if (energies) book_energy(sidata, pair_law, scale, k, f, ut_before, dt_history, began);
      for (int c = 0; c < 3; c++) ft[c] = f.ft[c];
      mn::torque3(k, f, sidata.radi, torque_i);
      if (!sidata.is_wall) mn::torque3(k, f, sidata.radj, torque_j);
    }

    if (sidata.is_wall) {
      const double area_ratio = sidata.area_ratio;
      for (int c = 0; c < 3; c++) {
        i_forces.delta_F[c] += ft[c] * area_ratio;
        i_forces.delta_torque[c] += torque_i[c] * area_ratio;
      }
    } else {
      for (int c = 0; c < 3; c++) {
        i_forces.delta_F[c] += ft[c];
        j_forces.delta_F[c] -= ft[c];
        i_forces.delta_torque[c] += torque_i[c];
        j_forces.delta_torque[c] += torque_j[c];    // both turn the same way
      }
    }
  }

  // LIGGGHTS calls this for a pair that is apart but closer than the contact distance factor
  // times the radii's sum (a factor above 1 only where a deck or another model asks for one),
  // and for a wall's contact as far out: the contact has ended, the next begins anew
  void surfacesClose(SurfacesCloseData &scdata, ForceData &, ForceData &)
  {
    if (scdata.contact_flags) *scdata.contact_flags &= ~CONTACT_TANGENTIAL_MODEL;
    if (!scdata.contact_history) return;
    scdata.contact_history[seen_offset] = 0.0;
    for (int c = 0; c < 3; c++) scdata.contact_history[ut_offset + c] = 0.0;
  }

  // a force evaluation of the pair style (walls evaluate without); one that moves the particles
  // on (compute pair/gran/local's are not) books energies
  void beginPass(SurfacesIntersectData &sidata, ForceData &, ForceData &)
  {
    ++passes;
    booking = energies && sidata.computeflag;
    if (booking) {
      pair = dynamic_cast<LAMMPS_NS::PairGran *>(force->pair_match("gran", 0));
      frozen_bit = pair->freeze_group_bit();
    }
  }
  void endPass(SurfacesIntersectData &sidata, ForceData &, ForceData &)
  {
    if (booking) book_ended(sidata.shearupdate ? update->dt : 0.0);
  }

 private:
  // Whether the contact, touching at this evaluation, begins at it; `seen` is its history's
  // record of the pass that last found it touching, set to this one. LIGGGHTS clears a pair's
  // history when it builds a neighbour list with the pair apart, but calls surfacesClose,
  // where a model could see a contact end in between, only for pairs closer than neighbor's
  // contact distance factor times the radii's sum: 1 by default, never. (A factor that covers
  // every listed pair widens the lists by as much: twice the pairs in the 3D chute.) So a
  // pair's contact continues if the previous pass found it touching. A wall's evaluation has
  // no passes: LIGGGHTS clears a wall contact's history each time it finds the particle apart,
  // and a wall contact continues where its history holds any pass; so does a pair at the pair
  // style's first pass, a run's setup, where its history is that of a restart file (or zero).
  bool begins(double &seen) const
  {
    const bool continues = passes > 1 ? seen == passes - 1 : seen != 0.0;
    seen = passes > 1 ? passes : 1;
    return !continues;
  }

  // i's share of a touching contact, and j's where j is owned here (newton off: a pair with a
  // ghost is computed by both processes)
  GRANMN_CALLED void count(const SurfacesIntersectData &sidata, bool began)
  {
    const granmn::ContactTallies &tallies = counter->tallies();
    tallies.add(sidata.i, granmn_liggghts::partner_is_boundary(sidata), began);
    if (!sidata.is_wall && sidata.j < atom->nlocal)
      tallies.add(sidata.j, granmn_liggghts::i_is_boundary(sidata), began);
  }

  // A touching contact's energies booked (mn::book_contact_energy; its energy history anew
  // where it began, its account opened at a run's setup: mn::open_energy_account), its shares
  // to its atoms: half to each of two particles, all to the mobile one against a frozen
  // particle (told by fix freeze's group: meff, which the counters read, cannot tell which of
  // two particles of one mass is the frozen one).
  template <class K, class F>
  GRANMN_CALLED void book_energy(const SurfacesIntersectData &sidata, const mn::Law &pair_law,
                                 double scale, const K &k, const F &f, double ut_before,
                                 double dt_history, bool began)
  {
    double *energy = &sidata.contact_history[energy_offset];
    const int size = mn::energy_history_size(mn::Integrator::VelocityVerlet, dimension);
    if (began)
      for (int s = 0; s < size; s++) energy[s] = 0.0;
    const double *ut = &sidata.contact_history[ut_offset];
    const double ut_after = ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2];
    const double lever[3] = {sidata.radi * sidata.omega_i[0] + sidata.radj * sidata.omega_j[0],
                             sidata.radi * sidata.omega_i[1] + sidata.radj * sidata.omega_j[1],
                             sidata.radi * sidata.omega_i[2] + sidata.radj * sidata.omega_j[2]};
    const mn::EnergyStep booked = book(pair_law, scale, k, lever, f, ut_before, ut_after,
                                       dt_history, energy);
    const mn::StoredEnergy stored = mn::stored_energy(pair_law, scale, k.delta, ut_after);
    const int *mask = atom->mask;
    const bool i_frozen = mask[sidata.i] & frozen_bit, j_frozen = mask[sidata.j] & frozen_bit;
    share(sidata.i, sidata.j, i_frozen, j_frozen, booked, stored);
    if (began && dt_history == 0.0)
      share(sidata.i, sidata.j, i_frozen, j_frozen,
            mn::open_energy_account(pair_law, scale, k.delta, ut_after, energy), {0.0, 0.0});
  }

  static mn::EnergyStep book(const mn::Law &law, double scale, const mn::Kinematics &k,
                             const double lever[3], const mn::Force &f, double before,
                             double after, double dt, double *energy)
  {
    return mn::book_contact_energy(law, scale, k, lever[2], f, before, after, dt,
                                   mn::Integrator::VelocityVerlet, energy);
  }

  static mn::EnergyStep book(const mn::Law &law, double scale, const mn::Kinematics3 &k,
                             const double lever[3], const mn::Force3 &f, double before,
                             double after, double dt, double *energy)
  {
    return mn::book_contact_energy(law, scale, k, lever, f, before, after, dt, energy);
  }

  // The share of a contact's energies that goes to i: half of a contact of two particles, all
  // of one with a frozen particle to the mobile one.
  static double share_of_i(bool i_frozen, bool j_frozen)
  {
    return i_frozen ? 0.0 : j_frozen ? 1.0 : 0.5;
  }

  // i's share, and j's where j is owned here (newton off: a pair with a ghost is booked by both
  // processes)
  void share(int i, int j, bool i_frozen, bool j_frozen, const mn::EnergyStep &booked,
             const mn::StoredEnergy &stored) const
  {
    const double share_i = share_of_i(i_frozen, j_frozen);
    energies->add(i, share_i, booked, stored);
    if (j < atom->nlocal) energies->add(j, 1.0 - share_i, booked, stored);
  }

  // After a pass: the contacts the previous pass found touching and this one did not have
  // ended. The model is not called for them (LIGGGHTS calls surfacesClose only within the
  // contact distance factor), so they are looked up: each one's last force's second half and
  // its tangential spring's release booked (mn::book_ended_contact_energy) from the particles'
  // state now, as the plugin's pair style books them at its first evaluation after the end.
  // Where the pass's neighbour list was built at this step, LIGGGHTS dropped the history of
  // every pair it found apart; fix contact/history still holds each atom's copy, seen from it
  // (taken at the build, before the particles were exchanged), for its partners of the last
  // list: each ended contact is booked from each of its atoms' copies, to that atom only. Else
  // they are in the pass's list, booked to both atoms from the pair's history.
  GRANMN_CALLED void book_ended(double dt_history)
  {
    if (passes < 2 || !pair->listgranhistory) return;
    if (neighbor->ago == 0) {
      LAMMPS_NS::FixContactHistory *copies = pair->get_fix_history();
      double **x = atom->x;
      const double *radius = atom->radius;
      for (int i = 0; i < atom->nlocal; i++)
        for (int m = 0; m < copies->n_partner(i); m++) {
          double *contact = copies->contacthistory(i, m);
          if (contact[seen_offset] != passes - 1) continue;
          const int j = domain->closest_image(i, atom->map(copies->partner(i, m)));
          if (j < 0) continue;
          const double d[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
          const double radsum = radius[i] + radius[j];
          if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < radsum * radsum) continue;
          book_ended_contact(i, j, contact, dt_history, false);
        }
      return;
    }
    const NeighList *list = pair->list;
    double **history = pair->listgranhistory->firstdouble;
    const int stride = pair->dnum();
    for (int ii = 0; ii < list->inum; ii++) {
      const int i = list->ilist[ii];
      const int *jlist = list->firstneigh[i];
      for (int jj = 0; jj < list->numneigh[i]; jj++) {
        double *contact = &history[i][stride * jj];
        if (contact[seen_offset] == passes - 1)
          book_ended_contact(i, jlist[jj] & NEIGHMASK, contact, dt_history, true);
      }
    }
  }

  // One ended contact of i and j, its history seen from i: booked to i, and to j if `both`
  // (and j is owned here).
  void book_ended_contact(int i, int j, double *contact, double dt_history, bool both)
  {
    double **x = atom->x, **v = atom->v, **omega = atom->omega;
    const double *radius = atom->radius, *rmass = atom->rmass, *mass = atom->mass;
    const int *type = atom->type, *mask = atom->mask;
    const double d[3] = {x[i][0] - x[j][0], x[i][1] - x[j][1], x[i][2] - x[j][2]};
    const double dv[3] = {v[i][0] - v[j][0], v[i][1] - v[j][1], v[i][2] - v[j][2]};
    const double lever[3] = {radius[i] * omega[i][0] + radius[j] * omega[j][0],
                             radius[i] * omega[i][1] + radius[j] * omega[j][1],
                             radius[i] * omega[i][2] + radius[j] * omega[j][2]};
    const double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double radsum = radius[i] + radius[j];
    const double mi = rmass ? rmass[i] : mass[type[i]], mj = rmass ? rmass[j] : mass[type[j]];
    const bool i_frozen = mask[i] & frozen_bit, j_frozen = mask[j] & frozen_bit;
    // the mass scale as granmn_liggghts::mass_scale takes it from LIGGGHTS's meff
    const double meff = i_frozen ? mj : j_frozen ? mi : mi * mj / (mi + mj);
    const double scale = (i_frozen || j_frozen ? mn::boundary_mass_scale(meff) : 2.0 * meff) *
        law.laws.force_per_mass_acceleration;
    const mn::Law &pair_law = law.laws(type[i], type[j]);
    const double *ut = contact + ut_offset;
    const double ut_squared = ut[0] * ut[0] + ut[1] * ut[1] + ut[2] * ut[2];
    double *energy = contact + energy_offset;
    const mn::EnergyStep booked =
        law.two_d ? mn::book_ended_contact_energy(
                        pair_law, scale, mn::kinematics(mn::Dim<2>(), d, r, radsum, dv, lever),
                        lever[2], ut_squared, dt_history, mn::Integrator::VelocityVerlet, energy)
                  : mn::book_ended_contact_energy(
                        pair_law, scale, mn::kinematics(mn::Dim<3>(), d, r, radsum, dv, lever),
                        lever, ut_squared, dt_history, energy);
    if (both) {
      share(i, j, i_frozen, j_frozen, booked, {0.0, 0.0});
    } else {
      energies->add(i, share_of_i(i_frozen, j_frozen), booked, {0.0, 0.0});
    }
  }

  int seen_offset, ut_offset;
  int energy_offset = -1;    // the energy history's first value (energy on), else -1
  bool keeps_energy = false, wall = false, booking = false;
  int dimension = 3;
  const granmn::EnergyTallies *energies = nullptr;    // fix contacts/mn energy yes's
  LAMMPS_NS::PairGran *pair = nullptr;    // the pair style, and fix freeze's group bit, where
  int frozen_bit = 0;                     // a pass books energies
  // the pair style's passes so far: a history's record of one is exact in a double
  long long passes = 0;
  const granmn::ContactCounter *counter = nullptr;
  granmn_liggghts::ModelLaw law;
};

}    // namespace ContactModels
}    // namespace LIGGGHTS
#endif
#endif
