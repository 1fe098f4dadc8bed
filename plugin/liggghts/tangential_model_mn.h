/* LIGGGHTS 3.8 tangential model `mn`: the tangential force of the Mitarai-Nakanishi law, with
   normal model `mn` (docs/liggghts.md). The force is mn_contact.h's, as in the LAMMPS pair style
   gran/mn: the trial force -2M (k_t u_t + eta_t v_t), capped at mu |fn|, with u_t the integral
   of v_t over the contact (3 history values; in 2D the first holds the scalar u_t along t).
   Setting: coulomb_cutback on|off (off: the paper's literal u_t; on: u_t cut back to the
   Coulomb limit while sliding). It keeps the contact's history, and so tells when a contact
   begins: u_t starts from zero there, and with a fix contacts/mn defined it adds each touching
   contact to the fix's tallies at every evaluation, those begun counted as such. */
#ifdef TANGENTIAL_MODEL
TANGENTIAL_MODEL(TANGENTIAL_MN,mn,20)
#else
#ifndef TANGENTIAL_MODEL_MN_H_
#define TANGENTIAL_MODEL_MN_H_
#include "atom.h"
#include "contact_models.h"
#include "granmn_liggghts_law.h"
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
  }

  void postSettings(IContactHistorySetup *, ContactModelBase *) {}

  void connectToProperties(PropertyRegistry &registry)
  {
    law.connect(lmp, registry, "tangential mn");
    counter = granmn_liggghts::find_counter(lmp);
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

    double ft[3], torque_i[3] = {0.0, 0.0, 0.0}, torque_j[3] = {0.0, 0.0, 0.0};
    if (law.two_d) {
      // the kinematics model mn computed (granmn_liggghts::keep)
      const mn::Kinematics k = granmn_liggghts::kept2(sidata);
      mn::Force f = mn::tangential_force(pair_law, scale, k, sidata.Fn, ut, dt_history,
                                         mn::Integrator::VelocityVerlet, nullptr);
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

  // a force evaluation of the pair style (walls evaluate without)
  void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) { ++passes; }
  void endPass(SurfacesIntersectData &, ForceData &, ForceData &) {}

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

  int seen_offset, ut_offset;
  // the pair style's passes so far: a history's record of one is exact in a double
  long long passes = 0;
  const granmn::ContactCounter *counter = nullptr;
  granmn_liggghts::ModelLaw law;
};

}    // namespace ContactModels
}    // namespace LIGGGHTS
#endif
#endif
