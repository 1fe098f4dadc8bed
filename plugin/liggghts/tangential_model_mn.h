/* LIGGGHTS 3.8 tangential model `mn`: the tangential force of the Mitarai-Nakanishi law, with
   normal model `mn` (docs/liggghts.md). The force is mn_contact.h's, as in the LAMMPS pair style
   gran/mn: the trial force -2M (k_t u_t + eta_t v_t), capped at mu |fn|, with u_t the integral
   of v_t over the contact (3 history values; in 2D the first holds the scalar u_t along t).
   Setting: coulomb_cutback on|off (off: the paper's literal u_t; on: u_t cut back to the
   Coulomb limit while sliding). */
#ifdef TANGENTIAL_MODEL
TANGENTIAL_MODEL(TANGENTIAL_MN,mn,20)
#else
#ifndef TANGENTIAL_MODEL_MN_H_
#define TANGENTIAL_MODEL_MN_H_
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
  }

  void surfacesIntersect(const SurfacesIntersectData &sidata, ForceData &i_forces,
                         ForceData &j_forces)
  {
    if (sidata.contact_flags) *sidata.contact_flags |= CONTACT_TANGENTIAL_MODEL;
    const mn::Law &pair_law = law.laws(sidata.itype, sidata.jtype);
    const double scale =
        granmn_liggghts::mass_scale(sidata) * law.laws.force_per_mass_acceleration;
    double *ut = &sidata.contact_history[ut_offset];
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

  // the contact has ended: its u_t starts from zero at the next one
  void surfacesClose(SurfacesCloseData &scdata, ForceData &, ForceData &)
  {
    if (scdata.contact_flags) *scdata.contact_flags &= ~CONTACT_TANGENTIAL_MODEL;
    if (!scdata.contact_history) return;
    for (int c = 0; c < 3; c++) scdata.contact_history[ut_offset + c] = 0.0;
  }

  void beginPass(SurfacesIntersectData &, ForceData &, ForceData &) {}
  void endPass(SurfacesIntersectData &, ForceData &, ForceData &) {}

 private:
  int ut_offset;
  granmn_liggghts::ModelLaw law;
};

}    // namespace ContactModels
}    // namespace LIGGGHTS
#endif
#endif
