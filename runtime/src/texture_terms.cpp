#include "sandpaper/runtime/texture_terms.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "force_tables.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper::runtime {

TextureTerms::TextureTerms(const schema::PatchProgram& texture) {
  for (std::size_t i = 0; i < texture.terms.size(); ++i) {
    if (const auto* g = std::get_if<schema::GratingTerm>(&texture.terms[i])) {
      terms_.push_back(Term{g, nullptr, glm::dvec2{std::cos(g->orientation_rad), std::sin(g->orientation_rad)}});
    } else if (const auto* f = std::get_if<schema::HeightFieldTerm>(&texture.terms[i])) {
      terms_.push_back(Term{nullptr, f});
    } else {
      throw std::invalid_argument("texture terms: term " + std::to_string(i) + " is not a grating or a height field");
    }
  }
  // The evaluator's checks of the tables' shapes are the ones the lookups below rely on.
  const PatchEvaluator check(texture);
}

namespace {

// tables::grating_force with the grating's direction given: its cos and sin cost more than the rest
// of the lookup, and a surface's texture is looked up on every tick in contact. The same
// arithmetic in the same order, so the same bits (TextureTerms' test holds the two together); the
// 2-D lookup is left as it is, its inlining is part of the 2-D tick's measured figures.
glm::dvec2 grating_force_along(const schema::GratingTerm& grating, glm::dvec2 n, glm::dvec2 p) noexcept {
  const double u = (p.x * n.x + p.y * n.y) / grating.period_m;
  if (!std::isfinite(u)) return glm::dvec2{std::numeric_limits<double>::quiet_NaN()};
  const std::size_t size = grating.force_N.size();
  const double index = (u - std::floor(u)) * static_cast<double>(size);
  // index >= 0, so truncation is the floor: one rounding the less, the same bits.
  std::size_t i = static_cast<std::size_t>(index);
  double frac = index - static_cast<double>(i);
  if (i >= size) {  // u - floor(u) rounded up to 1: the start of the period again
    i = 0;
    frac = 0;
  }
  const double lo = grating.force_N[i];
  const double hi = grating.force_N[i + 1 == size ? 0 : i + 1];
  return (lo + frac * (hi - lo)) * n;
}

}  // namespace

glm::dvec2 TextureTerms::force_rt(glm::dvec2 p) const noexcept {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    return glm::dvec2{std::numeric_limits<double>::quiet_NaN()};
  glm::dvec2 sum{0, 0};
  for (const Term& t : terms_)
    sum += t.grating ? grating_force_along(*t.grating, t.direction, p) : tables::height_field_force(*t.field, p);
  return sum;
}

}  // namespace sandpaper::runtime
