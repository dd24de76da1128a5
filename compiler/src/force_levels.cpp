#include "sandpaper/compiler/force_levels.hpp"

#include <cmath>
#include <set>

namespace sandpaper::compiler {

ForceLevels count_force_levels(const schema::PatchProgram& p) {
  ForceLevels out;
  std::set<float> mags, values;
  auto add = [&](const std::vector<float>& table) {
    ++out.tables;
    out.samples += table.size();
    for (float f : table) {
      // +0 and -0 are one value: no force.
      values.insert(f == 0.0f ? 0.0f : f);
      if (f != 0.0f) mags.insert(std::abs(f));
    }
  };
  for (const auto& t : p.terms) {
    if (const auto* g = std::get_if<schema::GratingTerm>(&t)) add(g->force_N);
    else if (const auto* h = std::get_if<schema::HeightFieldTerm>(&t)) {
      add(h->force_x_N);
      add(h->force_y_N);
    }
  }
  out.magnitudes = mags.size();
  out.signed_values = values.size();
  return out;
}

}  // namespace sandpaper::compiler
