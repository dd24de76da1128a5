#pragma once
// Test helpers: a compiled material, its patch laid on a plane in 3-D, and points where its
// texture pushes.
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/shapes/mesh.hpp"
#include "test_support.hpp"

namespace sandpaper::shapes {

inline schema::PatchProgram compiled(const std::string& text) {
  auto r = test::shipped_compiler().compile_text(text);
  EXPECT_TRUE(r.ok()) << text;
  return *r.program;
}

// The patch laid flat: a rectangle W x H in the plane z = 0 whose UVs follow the glTF export's
// convention (u = x / W + 0.5, v = 0.5 - y / H), mapped into 3-D by the axes ex, ey (unit,
// orthogonal) and scaled along x by `stretch` (metres of surface per metre of patch along x).
inline Mesh laid(const schema::PatchProgram& p, glm::dvec3 ex, glm::dvec3 ey, double stretch = 1) {
  const double w = p.size_m[0], h = p.size_m[1];
  MeshData d;
  for (const auto& [x, y] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}) {
    d.vertices.push_back(x * w * stretch * ex + y * h * ey);
    d.uvs.push_back({x + 0.5, 0.5 - y});
  }
  d.triangles = {{0, 1, 2}, {0, 2, 3}};
  return Mesh::build_nonrt(std::move(d));
}

// Which of laid()'s two triangles holds patch point s (the diagonal runs from corner to corner).
inline std::uint32_t triangle_under(const schema::PatchProgram& p, glm::dvec2 s) { return s.y / p.size_m[1] > s.x / p.size_m[0] ? 1 : 0; }

// The 2-D patch's force (N) with the hand still at s (m, from the patch centre).
inline glm::dvec2 patch_force(runtime::PatchEvaluator& patch, glm::dvec2 s) {
  runtime::HandState hand;
  hand.position_m = s;
  return patch.force_rt(hand, 0);
}

// 20 points of the patch where its force is more than a tenth of the compiled maximum (on the walls
// of a grating, on the slopes of a height field), drawn with a fixed seed.
inline std::vector<glm::dvec2> points_with_force(const schema::PatchProgram& p) {
  runtime::PatchEvaluator patch(p);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(-0.45 * p.size_m[0], 0.45 * p.size_m[0]), y(-0.45 * p.size_m[1], 0.45 * p.size_m[1]);
  std::vector<glm::dvec2> out;
  while (out.size() < 20) {
    const glm::dvec2 s{x(rng), y(rng)};
    if (glm::length(patch_force(patch, s)) > 0.1 * p.max_lateral_force_N) out.push_back(s);
  }
  return out;
}

}  // namespace sandpaper::shapes
