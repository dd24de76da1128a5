#pragma once
// The patch program: what the compiler hands the runtime. Everything the servo tick needs is
// precomputed here (force tables in newtons), so the tick only samples and sums (thesis 3.4;
// Appendix B "Texture" and "Arrays" patch classes). SI units throughout. Format: docs/PATCH_FORMAT.md.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace sandpaper::schema {

inline constexpr std::uint32_t kPatchFormatVersion = 1;

// F = -k (p - centre), p the hand position relative to the patch centre (thesis EQ 1, App. B Spring).
struct SpringTerm {
  double stiffness_N_per_m = 0;
  double centre_m[2] = {0, 0};
};

// F = -b v (thesis EQ 2, App. B Viscous).
struct DamperTerm {
  double damping_Ns_per_m = 0;
};

// A grating: the lateral force depends only on u = p . n, n = (cos orientation, sin orientation).
// force_N[i] is the force along n at u = (i / size) * period; the runtime interpolates linearly
// and wraps. Thesis 3.5.2 (version-2 seed, scaled and repeated to the period).
struct GratingTerm {
  double period_m = 0;
  double orientation_rad = 0;
  std::vector<float> force_N;  // one period, size >= 2
};

// A height field's lateral-force gradient F = -k grad h sampled on a regular grid (thesis 3.4,
// EQ 12-13), in newtons. Sample (ix, iy) sits at origin + (ix * spacing_x, iy * spacing_y),
// row-major with x fastest. Outside the grid the force is zero unless `repeat` wraps it.
struct HeightFieldTerm {
  std::uint32_t nx = 0, ny = 0;
  double origin_m[2] = {0, 0};
  double spacing_m[2] = {0, 0};
  bool repeat = false;
  std::vector<float> force_x_N;  // nx * ny
  std::vector<float> force_y_N;  // nx * ny
};

using Term = std::variant<SpringTerm, DamperTerm, GratingTerm, HeightFieldTerm>;

// Where one number of the compiled program came from.
struct Provenance {
  std::string parameter;  // dotted name: "texture.period", "texture.max_lateral_force", "spring.stiffness"
  double value_si = 0;    // value in `si_unit`
  std::string si_unit;    // "m", "N", "N/m", "N*s/m", "rad", "1"
  std::string stated;     // as the source wrote it, e.g. "3.2 mm", "roughness 0.55"
  std::string layer;      // "representative", "perceptual", "physical", "default", "derived"
  std::string source;     // "examples/corduroy.hmat:5:3", "library corduroy (corduroy.hmat:6:3)", "calibration ..."
};

struct CompileWarning {
  std::string code;     // stable identifier, e.g. "W0301"
  std::string message;
};

struct PatchProgram {
  std::string name;        // material name, e.g. "corduroy/wide-wale"
  std::string describes;   // the representative intent, kept verbatim (thesis 1.5.2)
  std::string device;      // device calibration the program was compiled for, e.g. "sim"
  double size_m[2] = {0.095, 0.095};  // patch width, height; centred on (0, 0)
  std::vector<Term> terms;            // summed each tick, in order
  double max_lateral_force_N = 0;     // texture's maximum lateral force over the patch less its rim
  double roughness = 0;               // ratio-scale roughness the map predicts for that force
  std::string roughness_map;          // id of the map used, e.g. "minsky1995-fig19"
  std::vector<Provenance> provenance;
  std::vector<CompileWarning> warnings;
};

}  // namespace sandpaper::schema
