// A material's texture on a surface (shapes/surface_texture.hpp) against the same material played
// on a 2-D patch by the runtime's evaluator, and against the gradient algorithm's closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <glm/geometric.hpp>

#include "allocation_counter.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/surface_texture.hpp"
#include "patch_on_plane.hpp"

namespace sandpaper::shapes {
namespace {

// A flat textured plane in 3-D gives the 2-D patch's lateral force within 1 %,
// at 20 points, for a grating along x, an oblique one and a height field.
TEST(SurfaceTexture, AFlatPlaneGivesThePatchsForceAtTwentyPoints) {
  for (const std::string text : {"like corduroy", "grating period 3 mm hill 40% orientation 30 deg; roughness 0.5",
                                 "like sandpaper-p60"}) {
    const auto p = compiled(text);
    const Mesh mesh = laid(p, {1, 0, 0}, {0, 1, 0});
    auto texture = SurfaceTexture::for_program_nonrt(p);
    runtime::PatchEvaluator patch(p);
    for (const glm::dvec2 s : points_with_force(p)) {
      const glm::dvec2 f2 = patch_force(patch, s);
      const glm::dvec3 f3 = texture.force_rt(mesh, triangle_under(p, s), {s.x, s.y, 0.0});
      EXPECT_LE(glm::length(glm::dvec2{f3.x, f3.y} - f2), 0.01 * glm::length(f2)) << text << " at " << s.x << ", " << s.y;
      EXPECT_EQ(f3.z, 0.0);
    }
  }
}

// Tilted in 3-D, the same force in the surface's own axes, and none along its normal.
TEST(SurfaceTexture, ATiltedPlaneCarriesTheForceInItsOwnAxes) {
  const auto p = compiled("grating period 3 mm hill 40% orientation 30 deg; roughness 0.5");
  const double a = 0.6;
  const glm::dvec3 ex{std::cos(a), 0, std::sin(a)}, ey{0, 1, 0};
  const Mesh mesh = laid(p, ex, ey);
  auto texture = SurfaceTexture::for_program_nonrt(p);
  runtime::PatchEvaluator patch(p);
  const glm::dvec3 n = glm::cross(ex, ey);
  for (const glm::dvec2 s : points_with_force(p)) {
    const glm::dvec2 f2 = patch_force(patch, s);
    // Above the surface by 2 mm: the point's foot on the plane is what counts.
    const glm::dvec3 at = s.x * ex + s.y * ey + 0.002 * n;
    const glm::dvec3 f3 = texture.force_rt(mesh, triangle_under(p, s), at);
    EXPECT_NEAR(glm::dot(f3, ex), f2.x, 0.01 * glm::length(f2));
    EXPECT_NEAR(glm::dot(f3, ey), f2.y, 0.01 * glm::length(f2));
    EXPECT_NEAR(glm::dot(f3, n), 0.0, 1e-12);
  }
}

// F = -k grad h on the surface: a texture stretched to twice its length along x has half its
// slope there, so half the force along x, and the same force along y (a grating across y).
TEST(SurfaceTexture, AStretchedTextureHasTheGradientOfItsStretchedHeights) {
  const auto p = compiled("grating period 3 mm hill 40% orientation 30 deg; roughness 0.5");
  const Mesh mesh = laid(p, {1, 0, 0}, {0, 1, 0}, 2.0);
  auto texture = SurfaceTexture::for_program_nonrt(p);
  runtime::PatchEvaluator patch(p);
  for (const glm::dvec2 s : points_with_force(p)) {
    const glm::dvec2 f2 = patch_force(patch, s);
    const glm::dvec3 f3 = texture.force_rt(mesh, triangle_under(p, s), {2 * s.x, s.y, 0.0});
    EXPECT_NEAR(f3.x, 0.5 * f2.x, 1e-9 + 1e-6 * std::abs(f2.x));
    EXPECT_NEAR(f3.y, f2.y, 1e-9 + 1e-6 * std::abs(f2.y));
  }
}

// On a sphere whose equator is 20 periods of a grating along u (W = 2 pi r), the force repeats
// every period of arc along the equator, and across the UV seam (u from 1 back to 0) it changes by
// no more than over the same arc elsewhere.
TEST(SurfaceTexture, OnASphereTheGratingRepeatsByArcLengthAndCrossesTheSeam) {
  const auto p = compiled("grating period 5 mm hill 50%; roughness 0.5");
  const double period = 0.005, r = 20 * period / (2 * std::numbers::pi);
  const Mesh mesh = uv_sphere(r, 1024, 64);
  auto texture = SurfaceTexture::for_program_nonrt(p, glm::dvec2{2 * std::numbers::pi * r, std::numbers::pi * r});
  // The triangle under a point on the equator at longitude lon (the UV sphere's band just north of
  // it; on the facet's plane).
  const auto on_equator = [&](double lon) {
    const glm::dvec3 at{r * std::cos(lon), r * std::sin(lon), 1e-7};
    for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
      const auto& f = mesh.frame(t);
      const glm::dvec3 w = at - mesh.vertex0(t);
      const double b1 = glm::dot(f.dual1, w), b2 = glm::dot(f.dual2, w);
      if (b1 >= -1e-12 && b2 >= -1e-12 && b1 + b2 <= 1 + 1e-12 && std::abs(glm::dot(f.normal, w)) < 1e-4)
        return texture.force_rt(mesh, t, at);
    }
    ADD_FAILURE() << "no triangle under longitude " << lon;
    return glm::dvec3{0.0};
  };
  const auto along = [&](double lon) { return glm::dot(on_equator(lon), glm::dvec3{-std::sin(lon), std::cos(lon), 0}); };
  const double arc = period / r;  // one period of arc, rad
  double largest = 0;
  for (int i = 0; i < 40; ++i) {
    const double lon = 0.1 + i * arc / 40;
    // Along the equator's tangent at each point: the surface turns by 54 degrees over 3 periods.
    const double f = along(lon), g = along(lon + 3 * arc);
    EXPECT_NEAR(f, g, 0.01 * p.max_lateral_force_N) << lon;
    largest = std::max(largest, std::abs(f));
  }
  EXPECT_GT(largest, 0.9 * p.max_lateral_force_N);  // the walls were met, so the repeat is not of zeros
  // Across the seam at longitude 0 against a step of the same size elsewhere, at the same phase.
  const double step = 1e-5 / r;
  for (int i = -3; i <= 3; ++i) {
    const double phase = i * arc / 8;
    const double across = std::abs(along(phase + step / 2) - along(phase - step / 2 + (phase == 0 ? 2 * std::numbers::pi : 0)));
    const double elsewhere = std::abs(along(phase + 5 * arc + step / 2) - along(phase + 5 * arc - step / 2));
    EXPECT_LE(across, elsewhere + 0.01 * p.max_lateral_force_N) << phase;
  }
}

TEST(SurfaceTexture, AMaterialWithoutATextureIsRefused) {
  EXPECT_THROW(SurfaceTexture::for_program_nonrt(compiled("spring 200 N/m")), std::invalid_argument);
  EXPECT_THROW(SurfaceTexture::for_program_nonrt(compiled("like corduroy"), glm::dvec2{0.0, 0.1}), std::invalid_argument);
}

TEST(SurfaceTexture, TheForceAllocatesNothingAndLocksNothing) {
  const auto p = compiled("like corduroy");
  const Mesh mesh = laid(p, {1, 0, 0}, {0, 1, 0});
  auto texture = SurfaceTexture::for_program_nonrt(p);
  double sum = 0;
  sandpaper::test::RtViolations violations;
  {
    sandpaper::test::CountedRtViolations counted;
    for (int i = 0; i < 10000; ++i) {
      const glm::dvec3 at{-0.04 + 0.08 * i / 10000.0, 0.01, 0.0};
      sum += texture.force_rt(mesh, 0, at).x;
    }
    violations = counted.stop();
  }
  EXPECT_EQ(violations.allocations, 0u);
  EXPECT_EQ(violations.locks, 0u);
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace sandpaper::shapes

namespace sandpaper::shapes {
namespace {

// Near a UV sphere's pole every line of longitude meets, the UVs squeeze the texture without bound
// and so would its slope: the force is held to the material's compiled maximum there.
TEST(SurfaceTexture, AtAUvSpheresPoleTheForceIsHeldToTheCompiledMaximum) {
  const auto p = compiled("grating period 3.2 mm hill 60%; roughness 0.45");
  const double r = 0.04;
  const Mesh mesh = uv_sphere(r, 256, 128);
  auto texture = SurfaceTexture::for_program_nonrt(p, glm::dvec2{2 * std::numbers::pi * r, std::numbers::pi * r});
  double largest = 0, unclamped_would_be = 0;
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles()[t];
    const glm::dvec3 c = (mesh.vertices()[tri[0]] + mesh.vertices()[tri[1]] + mesh.vertices()[tri[2]]) / 3.0;
    if (c.z < r * std::cos(0.05)) continue;  // within 0.05 rad of the north pole
    largest = std::max(largest, glm::length(texture.force_rt(mesh, t, c)));
    const TriangleFrame& f = mesh.frame(t);
    unclamped_would_be = std::max(unclamped_would_be, 2 * std::numbers::pi * r * glm::length(f.grad_u) * p.max_lateral_force_N);
  }
  // The squeeze is real (the unclamped gradient would give more than ten times the maximum) ...
  EXPECT_GT(unclamped_would_be, 10 * p.max_lateral_force_N);
  // ... and the force stays within it.
  EXPECT_LE(largest, p.max_lateral_force_N * (1 + 1e-12));
  EXPECT_GT(largest, 0.5 * p.max_lateral_force_N);
}

}  // namespace
}  // namespace sandpaper::shapes
