#include "sandpaper/compiler/recovered_height_field.hpp"

#include <algorithm>
#include <cmath>

#include "sandpaper/compiler/textures.hpp"

namespace sandpaper::compiler {
namespace {

std::optional<RecoveredHeightField> grating_heights(const schema::GratingTerm& g, std::string& why) {
  const std::size_t n = g.force_N.size();
  double mean = 0, k = 0;
  for (float f : g.force_N) mean += f, k = std::max(k, std::abs(static_cast<double>(f)));
  if (!(k > 0) || n < 2) {
    why = "its grating has no force";
    return std::nullopt;
  }
  mean /= static_cast<double>(n);
  // Backward differences inverted exactly: h_i = h_{i-1} - du F_i / k. The table's mean (float
  // rounding) is taken out so that the heights close on themselves over a period.
  RecoveredHeightField t;
  const double du = g.period_m / static_cast<double>(n);
  t.h_m.assign(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) t.h_m[i] = t.h_m[i - 1] - du * (g.force_N[i] - mean) / k;
  t.kind = "grating";
  t.nx = static_cast<int>(n);
  t.ny = 1;
  t.spacing_m[0] = du;
  t.k_N = k;  // steepest slope 1 (45 degrees): a nominal relief
  t.repeat = true;
  t.period_m = g.period_m;
  t.orientation_rad = g.orientation_rad;
  return t;
}

std::optional<RecoveredHeightField> height_field_heights(const schema::HeightFieldTerm& term, const schema::PatchProgram& program,
                                                   const ResolvedMaterial* material, std::string& why) {
  const auto* hm = material ? std::get_if<ResolvedHeightmap>(&material->texture) : nullptr;
  if (!hm) {
    why = material ? "its height field is a generated pattern, whose heights are not kept yet"
                   : "its height field's heights are not known (a compiled program keeps only its forces)";
    return std::nullopt;
  }
  // Built again as codegen built it, keeping the heights this time.
  const bool stylus = hm->stylus() && !material->max_lateral_force;
  Diagnostics scratch;
  auto build = make_height_field(*hm, stylus ? std::nullopt : std::optional<double>(program.max_lateral_force_N), scratch,
                                 /*keep_heights=*/true);
  if (!build || build->term.nx != term.nx || build->term.ny != term.ny) {
    why = "its height map '" + hm->stated_path + "' no longer gives the compiled field";
    return std::nullopt;
  }
  RecoveredHeightField t;
  // Heights in metres: the stylus reading's are (k = press); otherwise a nominal relief whose
  // steepest slope inside the rim is 1, so k is the maximum lateral force.
  t.nominal = !stylus;
  t.k_N = stylus ? build->gain : program.max_lateral_force_N;
  const double to_m = stylus ? 1.0 : build->gain / t.k_N;
  t.h_m.resize(build->heights.size());
  for (std::size_t i = 0; i < t.h_m.size(); ++i) t.h_m[i] = build->heights[i] * to_m;
  t.kind = "height_field";
  t.nx = static_cast<int>(term.nx);
  t.ny = static_cast<int>(term.ny);
  std::copy_n(term.origin_m, 2, t.origin_m);
  std::copy_n(term.spacing_m, 2, t.spacing_m);
  t.repeat = term.repeat;
  return t;
}

}  // namespace

std::optional<RecoveredHeightField> recover_height_field(const schema::PatchProgram& program, const ResolvedMaterial* material,
                                              std::string& why) {
  for (const auto& term : program.terms) {
    if (const auto* g = std::get_if<schema::GratingTerm>(&term)) return grating_heights(*g, why);
    if (const auto* h = std::get_if<schema::HeightFieldTerm>(&term)) return height_field_heights(*h, program, material, why);
  }
  why = "it has no texture (no grating or height field)";
  return std::nullopt;
}

}  // namespace sandpaper::compiler
