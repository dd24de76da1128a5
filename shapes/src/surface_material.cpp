#include "sandpaper/shapes/surface_material.hpp"

#include <cmath>

namespace sandpaper::shapes {

std::string material_problem(std::span<const SurfaceMaterial> materials) {
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const SurfaceMaterial& m = materials[i];
    const std::string which = "material " + std::to_string(i) + ": ";
    if (!(std::isfinite(m.stiffness_N_per_m) && m.stiffness_N_per_m > 0.0)) return which + "stiffness must be > 0 N/m";
    if (!(std::isfinite(m.damping_Ns_per_m) && m.damping_Ns_per_m >= 0.0)) return which + "damping must be >= 0 N s/m";
    if (!(std::isfinite(m.static_friction) && m.static_friction >= 0.0)) return which + "static friction must be >= 0";
    if (!(std::isfinite(m.kinetic_friction) && m.kinetic_friction >= 0.0 && m.kinetic_friction <= m.static_friction)) {
      return which + "kinetic friction must be between 0 and the static friction";
    }
  }
  return {};
}

}  // namespace sandpaper::shapes
