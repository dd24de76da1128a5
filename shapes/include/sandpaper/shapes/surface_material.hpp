#pragma once
// What the proxy renderer needs to know about a surface: its spring, its damper and its Coulomb
// friction (Ruspini, Kolarov & Khatib 1997: a static and a kinetic friction cone).
#include <span>
#include <string>

namespace sandpaper::shapes {

struct SurfaceMaterial {
  double stiffness_N_per_m = 500.0;  // k: force = k (proxy - device), > 0
  double damping_Ns_per_m = 0.0;     // b: along the contact normal only, never pulling; >= 0
  double static_friction = 0.0;      // mu_s: the proxy sticks while |F_t| <= mu_s F_n
  double kinetic_friction = 0.0;     // mu_k <= mu_s: while sliding, |F_t| = mu_k F_n
};

// Empty when every material is usable, else what is wrong with the first that is not (for the
// renderer's constructor, and for a scene loader to report before it gets that far).
std::string material_problem(std::span<const SurfaceMaterial> materials);

}  // namespace sandpaper::shapes
