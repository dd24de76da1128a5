// The normal-force texture (shapes/surface_relief.hpp, the relief in textured_contact.hpp; Minsky
// 1995, 7.7.2): a surface carved by its texture's potential, felt through the contact's spring.
// Each figure against a closed form the test derives itself: a sine grating's force
// F = -A sin(2 pi u / P) has the potential U = -(A P / 2 pi) cos(2 pi u / P), so its carve is
// c = D (1 + cos(2 pi u / P)) / 2 (valleys, c = D, where the force points in from both sides).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "patch_on_plane.hpp"
#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/primitives.hpp"
#include "sandpaper/shapes/surface_relief.hpp"
#include "sandpaper/shapes/textured_contact.hpp"

namespace sandpaper::shapes {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kOffset = ProxyOptions{}.surface_offset_m;  // the proxy rests this far above

// A sine grating of `samples` per period, its normal at `orientation` (rad), on a 60 mm patch.
schema::PatchProgram sine_grating(double period_m, double amplitude_N, double orientation, std::size_t samples = 256) {
  schema::PatchProgram p;
  p.name = "sine grating";
  p.device = "sim";
  p.size_m[0] = p.size_m[1] = 0.06;
  schema::GratingTerm g;
  g.period_m = period_m;
  g.orientation_rad = orientation;
  for (std::size_t i = 0; i < samples; ++i)
    g.force_N.push_back(static_cast<float>(-amplitude_N * std::sin(2 * kPi * static_cast<double>(i) / static_cast<double>(samples))));
  p.terms.push_back(g);
  p.max_lateral_force_N = amplitude_N;
  return p;
}

// A measured figure as the test's XML output records it (--gtest_output=xml).
std::string g(double v) {
  char out[32];
  std::snprintf(out, sizeof out, "%.3g", v);
  return out;
}

double sine_carve(double depth, double period, double u) { return depth * 0.5 * (1 + std::cos(2 * kPi * u / period)); }

// The plane z = 0 with the patch laid on it (patch x, y = world x, y), k, no friction; the relief
// alone (`only`) or with the lateral texture.
struct ReliefPlane {
  schema::PatchProgram program;
  Mesh mesh;
  Bvh bvh;
  TexturedContact contact;
  ReliefPlane(schema::PatchProgram p, double k, double depth, bool lateral)
      : program(std::move(p)), mesh(laid(program, {1, 0, 0}, {0, 1, 0})), bvh(Bvh::build_nonrt(mesh)),
        contact(mesh, bvh, {SurfaceMaterial{k, 0, 0, 0}}, textures(program, lateral),
                reliefs(program, depth)) {}
  static std::vector<std::optional<SurfaceTexture>> textures(const schema::PatchProgram& p, bool lateral) {
    std::vector<std::optional<SurfaceTexture>> t(1);
    if (lateral) t[0] = SurfaceTexture::for_program_nonrt(p);
    return t;
  }
  static std::vector<std::optional<SurfaceRelief>> reliefs(const schema::PatchProgram& p, double depth) {
    std::vector<std::optional<SurfaceRelief>> r(1);
    r[0] = SurfaceRelief::for_program_nonrt(p, depth);
    return r;
  }
  // Pressed straight down to z = -press at (x, y), from just above.
  glm::dvec3 pressed(double x, double y, double press) {
    contact.reset_rt({x, y, 0.002});
    return contact.update_rt({x, y, -press});
  }
};

// At 20 points across a period, pressed deeper than the relief: the normal force is
// k (delta - c) within 1 %, c the sine grating's closed-form carve (along its normal at 0.5 rad).
TEST(SurfaceRelief, OnASineGratingTheNormalForceIsTheSpringPressedIntoTheCarve) {
  const double period = 0.004, depth = 0.0005, k = 1000, press = 0.001, a = 0.5;
  const glm::dvec2 n{std::cos(a), std::sin(a)}, along{-std::sin(a), std::cos(a)};
  ReliefPlane plane(sine_grating(period, 0.4, a), k, depth, /*lateral=*/false);
  const double delta = press + kOffset;
  double worst = 0;
  for (int i = 0; i < 20; ++i) {
    const double u = -0.5 * period + period * (i + 0.3) / 20;
    const glm::dvec2 s = u * n + 0.003 * along;  // off the grating's own axis: the direction counts
    const glm::dvec3 f = plane.pressed(s.x, s.y, press);
    const double want = k * (delta - sine_carve(depth, period, u));
    EXPECT_NEAR(f.z, want, 0.01 * want) << "u = " << u * 1e3 << " mm";
    worst = std::max(worst, std::abs(f.z - want) / want);
    EXPECT_NEAR(plane.contact.relief_depth_rt(), sine_carve(depth, period, u), 0.01 * depth);
  }
  RecordProperty("worst_relative_error", g(worst));
  // Pressed less than the valley is deep, the stylus hangs in it: no force at the valley's floor.
  const glm::dvec3 f = plane.pressed(0, 0, 0.0002);
  EXPECT_NEAR(glm::length(f), 0.0, 1e-9);
}

// The tangential part is the carved surface's slope times its normal force: k (delta - c) dc/du
// along the grating's normal, with dc/du a finite difference of the measured normal force / k
// (taken inside one table cell, where the interpolated carve is straight).
TEST(SurfaceRelief, TheTangentialForceIsTheSlopeOfTheMeasuredCarveTimesTheNormalForce) {
  const double period = 0.004, depth = 0.0005, k = 1000, press = 0.001, a = 0.5;
  const std::size_t samples = 256;
  const glm::dvec2 n{std::cos(a), std::sin(a)};
  ReliefPlane plane(sine_grating(period, 0.4, a, samples), k, depth, /*lateral=*/false);
  const double cell = period / samples;
  int checked = 0;
  double worst = 0;
  for (int i = 0; i < 20; ++i) {
    const double u = (std::floor((-0.5 + (i + 0.5) / 20) * samples) + 0.5) * cell;  // a cell's middle
    const double h = 0.25 * cell;
    const glm::dvec3 f = plane.pressed(u * n.x, u * n.y, press);
    const double fp = plane.pressed((u + h) * n.x, (u + h) * n.y, press).z;
    const double fm = plane.pressed((u - h) * n.x, (u - h) * n.y, press).z;
    const double slope = -(fp - fm) / (2 * h * k);  // dc/du from c = delta - F_n / k
    const glm::dvec2 want = f.z * slope * n;
    const glm::dvec2 got{f.x, f.y};
    EXPECT_LE(glm::length(got - want), 0.01 * glm::length(want) + 1e-9) << "u = " << u * 1e3 << " mm";
    if (glm::length(want) > 0.05) worst = std::max(worst, glm::length(got - want) / glm::length(want));
    // And that slope is the closed form's, -D (pi / P) sin(2 pi u / P), within the table's cell.
    EXPECT_NEAR(slope, -depth * kPi / period * std::sin(2 * kPi * u / period), 0.02 * depth * kPi / period);
    checked += glm::length(want) > 0.05 ? 1 : 0;
  }
  EXPECT_GE(checked, 10);  // most of the points are on a slope that pushes
  RecordProperty("worst_relative_error", g(worst));
}

// Frictionless, round a closed loop that goes into the surface, across grooves at changing depth
// (some shallower than the relief, where the stylus hangs in the valleys), and out again: the
// relief with the spring is one potential, so the net work is ~0.
TEST(SurfaceRelief, FrictionlessRoundAClosedLoopTheNetWorkIsZero) {
  const double period = 0.004, depth = 0.0005, k = 1000;
  for (const bool lateral : {false, true}) {
    ReliefPlane plane(sine_grating(period, 0.4, 0.3), k, depth, lateral);
    // Down at x = -6 mm, along x to +6 mm with the press going between 0.2 and 1.2 mm, across to
    // y = 2 mm, back along x at another depth profile, and up again.
    auto at = [&](double t) -> glm::dvec3 {  // t in [0, 5]
      const double s = t - std::floor(std::min(t, 4.999999));
      if (t < 1) return {-0.006, 0.0, 0.001 - 0.0017 * s};
      if (t < 2) return {-0.006 + 0.012 * s, 0.0, -(0.0007 + 0.0005 * std::sin(5 * kPi * s))};
      if (t < 3) return {0.006, 0.002 * s, -0.0007 + 0.0001 * s};
      if (t < 4) return {0.006 - 0.012 * s, 0.002 * (1 - s), -0.0006 - 0.0003 * std::sin(3 * kPi * s)};
      return {-0.006, 0.0, -0.0006 + 0.0016 * s};
    };
    const int steps = 500000;
    glm::dvec3 prev_x = at(0);
    plane.contact.reset_rt(prev_x + glm::dvec3{0, 0, 0.001});
    glm::dvec3 prev_f = plane.contact.update_rt(prev_x), prev_relief = plane.contact.relief_force_rt();
    double work = 0, relief_work = 0, largest = 0, path = 0;
    for (int i = 1; i <= steps; ++i) {
      const glm::dvec3 x = at(5.0 * i / steps);
      const glm::dvec3 f = plane.contact.update_rt(x);
      const glm::dvec3 relief = plane.contact.relief_force_rt();
      work += 0.5 * glm::dot(prev_f + f, x - prev_x);
      relief_work += 0.5 * glm::dot(prev_relief + relief, x - prev_x);
      largest = std::max(largest, glm::length(f));
      path += glm::length(x - prev_x);
      prev_x = x, prev_f = f, prev_relief = relief;
    }
    ASSERT_GT(largest, 0.5);  // it pressed in
    RecordProperty(lateral ? "relief_work_ratio_with_lateral" : "work_ratio_only",
                   g((lateral ? relief_work : work) / (largest * path)));
    // The relief's own share is a potential too (the spring's is, and so is their sum).
    EXPECT_LT(std::abs(relief_work), 1e-3 * largest * path) << "lateral " << lateral;
    if (!lateral) {
      EXPECT_LT(std::abs(work), 1e-3 * largest * path) << "work " << work << " J over " << path << " m";
    }
  }
}

// `only`: the surface's texture is felt through the relief alone; with the lateral texture kept,
// the difference is the patch's own lateral force.
TEST(SurfaceRelief, OnlyLeavesNoLateralForceBeyondTheReliefsSlope) {
  const double period = 0.004, depth = 0.0005, k = 1000, press = 0.001;
  ReliefPlane alone(sine_grating(period, 0.4, 0.0), k, depth, false);
  ReliefPlane both(sine_grating(period, 0.4, 0.0), k, depth, true);
  runtime::PatchEvaluator patch(alone.program);
  for (int i = 0; i < 20; ++i) {
    const double x = -0.002 + 0.004 * (i + 0.3) / 20;
    const glm::dvec3 f = alone.pressed(x, 0.001, press);
    EXPECT_EQ(alone.contact.texture_force_rt(), glm::dvec3{0.0});
    const glm::dvec3 relief = alone.contact.relief_force_rt();
    EXPECT_NEAR(f.x, relief.x, 1e-12);
    EXPECT_NEAR(f.y, relief.y, 1e-12);
    const glm::dvec3 g = both.pressed(x, 0.001, press);
    const glm::dvec2 lateral = patch_force(patch, {x, 0.001});
    EXPECT_NEAR(g.x - f.x, lateral.x, 1e-6 + 1e-6 * std::abs(lateral.x));
    EXPECT_NEAR(g.z, f.z, 1e-12);
  }
}

// A repeating height field sampled from U = A (cos(2 pi x / L) + 0.5 cos(2 pi y / L)), its forces
// -grad U at the samples: the carve is D (Umax - U) / (Umax - Umin), Umax - Umin = 3 A, within 1 %
// of D, also a period away (it repeats). Not repeating, outside the grid c is its edge's.
TEST(SurfaceRelief, AHeightFieldsCarveIsThePotentialOfItsForces) {
  const double L = 0.016, A = 1e-3, depth = 0.0004;
  const std::uint32_t n = 32;
  const double h = L / n;
  auto U = [&](double x, double y) { return A * (std::cos(2 * kPi * x / L) + 0.5 * std::cos(2 * kPi * y / L)); };
  for (const bool repeat : {true, false}) {
    schema::PatchProgram p;
    p.size_m[0] = p.size_m[1] = L;
    schema::HeightFieldTerm t;
    t.nx = t.ny = repeat ? n : n + 1;  // one period, closed by the repeat or by its last row
    t.origin_m[0] = t.origin_m[1] = -L / 2;
    t.spacing_m[0] = t.spacing_m[1] = h;
    t.repeat = repeat;
    for (std::uint32_t iy = 0; iy < t.ny; ++iy)
      for (std::uint32_t ix = 0; ix < t.nx; ++ix) {
        const double x = -L / 2 + ix * h, y = -L / 2 + iy * h;
        t.force_x_N.push_back(static_cast<float>(A * 2 * kPi / L * std::sin(2 * kPi * x / L)));
        t.force_y_N.push_back(static_cast<float>(A * 0.5 * 2 * kPi / L * std::sin(2 * kPi * y / L)));
      }
    p.terms.push_back(t);
    const SurfaceRelief relief = SurfaceRelief::for_program_nonrt(p, depth);
    for (int i = 0; i < 50; ++i) {
      const double x = -L / 2 + L * std::fmod(0.37 * i, 1.0), y = -L / 2 + L * std::fmod(0.61 * i + 0.1, 1.0);
      const double want = depth * (1.5 * A - U(x, y)) / (3 * A);
      EXPECT_NEAR(relief.depth_at_rt({x, y}), want, 0.01 * depth) << repeat << " at " << x << ", " << y;
      if (repeat) {
        EXPECT_NEAR(relief.depth_at_rt({x + 3 * L, y - L}), want, 0.01 * depth);
      }
    }
    if (!repeat) {
      // Past the right edge: the edge's value, and no slope across it.
      glm::dvec2 g;
      const double beyond = relief.depth_at_rt({L, 0.003}, &g);
      EXPECT_NEAR(beyond, relief.depth_at_rt({L / 2, 0.003}), 1e-12);
      EXPECT_EQ(g.x, 0.0);
      EXPECT_NEAR(relief.depth_at_rt({L / 2 - 1e-9, 0.003}), beyond, 1e-9);
    }
  }
}

// The slope is held to 1 where the UVs squeeze the texture: at a UV sphere's pole a 4 mm grating
// laid one circumference per unit of u is squeezed without bound.
TEST(SurfaceRelief, AtASpherePoleTheSlopeIsHeldToOne) {
  const double r = 0.04;
  const Mesh mesh = uv_sphere(r, 128, 64);
  const schema::PatchProgram p = sine_grating(0.004, 0.4, 0.0);
  const SurfaceRelief relief = SurfaceRelief::for_program_nonrt(p, 0.0005, glm::dvec2{2 * kPi * r, kPi * r});
  double largest = 0;
  for (std::uint32_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles()[t];
    const glm::dvec3 c = (mesh.vertices()[tri[0]] + mesh.vertices()[tri[1]] + mesh.vertices()[tri[2]]) / 3.0;
    glm::dvec3 g{0.0};
    (void)relief.carve_rt(mesh, t, c, g);
    EXPECT_LE(glm::length(g), 1.0 + 1e-12);
    EXPECT_NEAR(glm::dot(g, mesh.frame(t).normal), 0.0, 1e-12);  // along the surface
    largest = std::max(largest, glm::length(g));
  }
  EXPECT_GT(largest, 0.999);  // the hold was needed somewhere
}

TEST(SurfaceRelief, WhatItRefuses) {
  const schema::PatchProgram p = sine_grating(0.004, 0.4, 0.0);
  EXPECT_THROW((void)SurfaceRelief::for_program_nonrt(p, 0.0), std::invalid_argument);
  EXPECT_THROW((void)SurfaceRelief::for_program_nonrt(p, -1e-3), std::invalid_argument);
  EXPECT_THROW((void)SurfaceRelief::for_program_nonrt(p, NAN), std::invalid_argument);
  EXPECT_THROW((void)SurfaceRelief::for_program_nonrt(p, 1e-3, glm::dvec2{0.1, 0.0}), std::invalid_argument);
  schema::PatchProgram bare = p;
  bare.terms.clear();
  EXPECT_THROW((void)SurfaceRelief::for_program_nonrt(bare, 1e-3), std::invalid_argument);
  // A texture with no force carves nothing.
  schema::PatchProgram flat = p;
  for (float& f : std::get<schema::GratingTerm>(flat.terms[0]).force_N) f = 0;
  EXPECT_EQ(SurfaceRelief::for_program_nonrt(flat, 1e-3).depth_at_rt({0.001, 0.002}), 0.0);
}

}  // namespace
}  // namespace sandpaper::shapes
