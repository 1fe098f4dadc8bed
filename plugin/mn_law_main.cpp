// mn-law: prints the coefficients docs/model.md section 3 derives from (kn, e, beta, mu), and the
// stability limits, one "name value" per line, so that scripts use the header's numbers.
//   mn-law [--shape disc|sphere] KN E BETA [MU]
// The shape is the particles' inertia (section 3.1): discs (the 2D styles, the default) or solid
// spheres (the 3D styles).
#include "mn_integration.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

int main(int argc, char **argv)
{
  double q = mn::DISC_Q;
  if (argc > 2 && std::strcmp(argv[1], "--shape") == 0) {
    if (std::strcmp(argv[2], "sphere") == 0)
      q = mn::SOLID_SPHERE_Q;
    else if (std::strcmp(argv[2], "disc") != 0) {
      std::fprintf(stderr, "mn-law: --shape takes disc or sphere, not '%s'\n", argv[2]);
      return 2;
    }
    argc -= 2;
    argv += 2;
  }
  if (argc < 4 || argc > 5) {
    std::fprintf(stderr, "usage: mn-law [--shape disc|sphere] KN E BETA [MU]\n");
    return 2;
  }
  char *end = nullptr;
  double values[4] = {0.0, 0.0, 0.0, 0.0};
  for (int k = 1; k < argc; k++) {
    values[k - 1] = std::strtod(argv[k], &end);
    if (end == argv[k] || *end != '\0') {
      std::fprintf(stderr, "mn-law: '%s' is not a number\n", argv[k]);
      return 2;
    }
  }
  const mn::Material material{values[0], values[1], values[2], values[3]};
  if (const char *problem = mn::material_error(material)) {
    std::fprintf(stderr, "mn-law: %s\n", problem);
    return 2;
  }
  const mn::Law law = mn::derive(material, mn::Options(), q);
  std::printf("q %.17g\n", law.q);
  std::printf("kn %.17g\neta_n %.17g\nkt %.17g\neta_t %.17g\ntau_c %.17g\ntau_w %.17g\n"
              "e_w %.17g\ndt_max_verlet %.17g\ndt_max_ab2 %.17g\n",
              law.material.kn, law.eta_n, law.kt, law.eta_t, law.tau_c, law.tau_w, law.e_w,
              mn::max_stable_dt(law, mn::Integrator::VelocityVerlet),
              mn::max_stable_dt(law, mn::Integrator::AdamsBashforth2));
  return 0;
}
