#include "sandpaper/runtime/texture_terms.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "force_tables.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"

namespace sandpaper::runtime {

TextureTerms::TextureTerms(const schema::PatchProgram& texture) {
  for (std::size_t i = 0; i < texture.terms.size(); ++i) {
    if (const auto* g = std::get_if<schema::GratingTerm>(&texture.terms[i])) {
      terms_.push_back(Term{g, nullptr});
    } else if (const auto* f = std::get_if<schema::HeightFieldTerm>(&texture.terms[i])) {
      terms_.push_back(Term{nullptr, f});
    } else {
      throw std::invalid_argument("texture terms: term " + std::to_string(i) + " is not a grating or a height field");
    }
  }
  // The evaluator's checks of the tables' shapes are the ones the lookups below rely on.
  const PatchEvaluator check(texture);
}

glm::dvec2 TextureTerms::force_rt(glm::dvec2 p) const noexcept {
  if (!std::isfinite(p.x) || !std::isfinite(p.y))
    return glm::dvec2{std::numeric_limits<double>::quiet_NaN()};
  glm::dvec2 sum{0, 0};
  for (const Term& t : terms_)
    sum += t.grating ? tables::grating_force(*t.grating, p) : tables::height_field_force(*t.field, p);
  return sum;
}

}  // namespace sandpaper::runtime
