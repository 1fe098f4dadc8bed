// mn-collision-rules: rules (a) and (b) of mn_collision.h over the impact angle, for the figure
// of docs/hard_spheres.md (scripts/studies/collision_rules_figure.py draws it).
//   mn-collision-rules [E BETA MU] [ANGLES]
// Prints, for equal disks and for a disk against the boundary (rule (a) with the boundary's
// default e_w and beta_w, settings.h's boundary_defaults), at ANGLES impact angles
// phi = atan(|v_t|/|v_n|) evenly from 0 to 89.5 degrees, an impact of unit speed (v_n = -cos phi,
// v_t = sin phi) and the outgoing contact velocity under rule (a), rule (b) with the literal u_t
// and rule (b) with the cut-back u_t:
//   partner phi_deg vn_in vt_in a_vn a_vt b_literal_vn b_literal_vt b_cutback_vn b_cutback_vt
#include "settings.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

int main(int argc, char **argv)
{
  if (argc != 1 && argc != 4 && argc != 5) {
    std::cerr << "usage: mn-collision-rules [E BETA MU] [ANGLES]\n";
    return 1;
  }
  const double e = argc > 1 ? std::atof(argv[1]) : 0.7, beta = argc > 1 ? std::atof(argv[2]) : 0.7,
               mu = argc > 1 ? std::atof(argv[3]) : 0.5;
  const int angles = argc > 4 ? std::atoi(argv[4]) : 180;
  const mn::Material material{1.0, e, beta, mu};
  if (const char *why = mn::material_error(material)) {
    std::cerr << "ERROR: " << why << "\n";
    return 1;
  }
  if (angles < 2) {
    std::cerr << "ERROR: ANGLES = " << angles << " must be at least 2\n";
    return 1;
  }
  mn::Options cutback_options;
  cutback_options.coulomb_cutback = true;
  const mn::Law literal = mn::derive(material), cutback = mn::derive(material, cutback_options);
  const mn::PaperRule disk_rule{e, beta, mu};
  const mn::PaperRule boundary_rule = mn::ed::boundary_defaults(e, beta, mu);
  std::printf("# mn-collision-rules e %g beta %g mu %g (boundary: e_w %.10g beta_w %.10g)\n", e,
              beta, mu, boundary_rule.e, boundary_rule.beta);
  std::printf("# partner phi_deg vn_in vt_in a_vn a_vt b_literal_vn b_literal_vt b_cutback_vn "
              "b_cutback_vt\n");
  for (const bool boundary : {false, true}) {
    // equal unit disks: M = 1/2; against the boundary M = m_i = 1; q = 3 for both
    const double reduced_mass = boundary ? 1.0 : 0.5, q = mn::DISC_Q;
    const mn::Partner partner = boundary ? mn::Partner::Boundary : mn::Partner::Disk;
    for (int k = 0; k < angles; k++) {
      const double phi = 89.5 * k / (angles - 1) * mn::PI / 180.0;
      const mn::ContactVelocity in{-std::cos(phi), std::sin(phi)};
      const mn::ContactVelocity a = mn::after_impulse(
          in, mn::paper_impulse(boundary ? boundary_rule : disk_rule, reduced_mass, q, in),
          reduced_mass, q);
      const mn::ContactVelocity bl = mn::soft_limit_collision(literal, partner, in).out;
      const mn::ContactVelocity bc = mn::soft_limit_collision(cutback, partner, in).out;
      std::printf("%s %.6f %.12g %.12g %.12g %.12g %.12g %.12g %.12g %.12g\n",
                  boundary ? "boundary" : "disk", phi * 180.0 / mn::PI, in.vn, in.vt, a.vn, a.vt,
                  bl.vn, bl.vt, bc.vn, bc.vt);
    }
  }
  return 0;
}
