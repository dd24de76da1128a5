#include "sandpaper/runtime/texture_force.hpp"

#include <cmath>
#include <variant>

namespace sandpaper::runtime {

schema::PatchProgram texture_terms_of(const schema::PatchProgram& program) {
  schema::PatchProgram texture = program;
  texture.terms.clear();
  for (const auto& t : program.terms)
    if (std::holds_alternative<schema::GratingTerm>(t) || std::holds_alternative<schema::HeightFieldTerm>(t))
      texture.terms.push_back(t);
  return texture;
}

std::optional<TextureForce> TextureForce::for_program(const schema::PatchProgram& program) {
  auto texture = std::make_unique<schema::PatchProgram>(texture_terms_of(program));
  if (texture->terms.empty()) return std::nullopt;
  return TextureForce(std::move(texture));
}

TextureForce::TextureForce(std::unique_ptr<schema::PatchProgram> texture)
    : texture_(std::move(texture)), evaluator_(std::make_unique<PatchEvaluator>(*texture_)) {}

glm::dvec2 TextureForce::at_nonrt(glm::dvec2 position_m) {
  HandState hand;
  hand.position_m = position_m;
  const glm::dvec2 f = evaluator_->force_rt(hand, 0.0);
  max_N_ = std::max(max_N_, std::hypot(f.x, f.y));
  return f;
}

}  // namespace sandpaper::runtime
