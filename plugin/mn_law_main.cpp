// mn-law: prints the coefficients docs/model.md section 3 derives from (kn, e, beta, mu), and the
// stability limits, one "name value" per line, so that scripts use the header's numbers: q, kn,
// then the values the styles publish, under their names less the prefix mn_.
//   mn-law [--shape disc|sphere] KN E BETA [MU]
// The shape is the particles' inertia (section 3.1): discs (the 2D styles, the default) or solid
// spheres (the 3D styles).
//   mn-law --columns
// prints the styles' output schema (mn_output_schema.h), one table a line: its name, then its
// columns' names in order (kinds: name code pairs).
#include "mn_output_schema.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

static void print_columns()
{
  using namespace granmn::output;
  std::printf("counters");
  for (const char *name : COUNTER_NAMES) std::printf(" %s", name);
  std::printf("\nvector_extras");
  for (const char *name : EXTRA_NAMES) std::printf(" %s", name);
  std::printf("\nenergy_sums");
  for (const char *name : ENERGY_NAMES) std::printf(" %s", name);
  std::printf(" %s", IN_FLIGHT_NAME);
  std::printf("\nwall_work %s", WALL_WORK_NAME);
  std::printf("\nrows");
  for (const char *name : ROW_NAMES) std::printf(" %s", name);
  std::printf("\nrow_energy");
  for (const char *name : ROW_ENERGY_NAMES) std::printf(" %s", name);
  std::printf("\nkinds");
  for (const KindName &kind : KINDS) std::printf(" %s %d", kind.name, kind.code);
  std::printf("\npublished");
  for (const char *name : PUBLISHED_NAMES) std::printf(" %s", name);
  std::printf("\n");
}

int main(int argc, char **argv)
{
  if (argc == 2 && std::strcmp(argv[1], "--columns") == 0) {
    print_columns();
    return 0;
  }
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
  std::printf("q %.17g\nkn %.17g\n", law.q, law.material.kn);
  const std::size_t prefix = std::strlen(granmn::output::PUBLISHED_PREFIX);
  granmn::output::for_each_published(law, [prefix](const char *name, double value) {
    std::printf("%s %.17g\n", name + prefix, value);
  });
  return 0;
}
