// Contact with a textured surface (shapes/textured_contact.hpp): the proxy's spring along the
// normal, the patch's lateral force along the surface, and friction beside the texture.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "patch_on_plane.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/shapes/bvh.hpp"
#include "sandpaper/shapes/textured_contact.hpp"

namespace sandpaper::shapes {
namespace {

std::vector<std::optional<SurfaceTexture>> one_texture(const schema::PatchProgram& p) {
  std::vector<std::optional<SurfaceTexture>> t;
  t.emplace_back(SurfaceTexture::for_program_nonrt(p));
  return t;
}

// The check, through the whole contact: pressed 1 mm into a textured plane at 20 points,
// the force along the plane is the 2-D patch's within 1 %, and along the normal k d within 1 %.
TEST(TexturedContact, PressedIntoATexturedPlaneTheLateralForceIsThePatchs) {
  for (const std::string text : {"like corduroy", "grating period 3 mm hill 40% orientation 30 deg; roughness 0.5",
                                 "like sandpaper-p60"}) {
    const auto p = compiled(text);
    const Mesh mesh = laid(p, {1, 0, 0}, {0, 1, 0});
    const Bvh bvh = Bvh::build_nonrt(mesh);
    const double k = 800, d = 0.001;
    TexturedContact contact(mesh, bvh, {SurfaceMaterial{k, 0, 0, 0}}, one_texture(p));
    runtime::PatchEvaluator patch(p);
    for (const glm::dvec2 s : points_with_force(p)) {
      contact.reset_rt({s.x, s.y, 0.002});
      const glm::dvec3 f = contact.update_rt({s.x, s.y, -d});
      const glm::dvec2 f2 = patch_force(patch, s);
      EXPECT_LE(glm::length(glm::dvec2{f.x, f.y} - f2), 0.01 * glm::length(f2)) << text << " at " << s.x << ", " << s.y;
      EXPECT_NEAR(f.z, k * d, 0.01 * k * d);
    }
  }
}

TEST(TexturedContact, NoTextureOutOfContactOrOnAnUntexturedSurface) {
  const auto p = compiled("like corduroy");
  const Mesh mesh = laid(p, {1, 0, 0}, {0, 1, 0});
  const Bvh bvh = Bvh::build_nonrt(mesh);
  const glm::dvec2 s = points_with_force(p).front();
  TexturedContact textured(mesh, bvh, {SurfaceMaterial{800, 0, 0, 0}}, one_texture(p));
  textured.reset_rt({s.x, s.y, 0.004});
  EXPECT_EQ(textured.update_rt({s.x, s.y, 0.002}), glm::dvec3{0.0});  // above the surface
  std::vector<std::optional<SurfaceTexture>> none(1);
  TexturedContact plain(mesh, bvh, {SurfaceMaterial{800, 0, 0, 0}}, std::move(none));
  plain.reset_rt({s.x, s.y, 0.002});
  const glm::dvec3 f = plain.update_rt({s.x, s.y, -0.001});
  EXPECT_NEAR(f.x, 0.0, 1e-12);
  EXPECT_NEAR(f.y, 0.0, 1e-12);
  EXPECT_THROW(TexturedContact(mesh, bvh, {SurfaceMaterial{}}, {}), std::invalid_argument);
}

// Sliding across a grating at a steady press N with kinetic friction mu_k: the texture is the
// gradient of a periodic height, so over whole periods it adds nothing, and the mean force against
// the motion is mu_k N (within 2 %), while within a period the texture's ridges are felt on top.
TEST(TexturedContact, SlidingOverATextureTheMeanDragIsKineticFrictionTimesThePress) {
  const auto p = compiled("grating period 4 mm hill 50%; roughness 0.5");
  const Mesh mesh = laid(p, {1, 0, 0}, {0, 1, 0});
  const Bvh bvh = Bvh::build_nonrt(mesh);
  const double k = 1000, d = 0.002, mu_s = 0.6, mu_k = 0.4;
  TexturedContact contact(mesh, bvh, {SurfaceMaterial{k, 0, mu_s, mu_k}}, one_texture(p));
  contact.reset_rt({-0.03, 0.0, 0.002});
  contact.update_rt({-0.03, 0.0, -d});
  // Move 5 mm to get sliding, then 10 periods (40 mm) in 0.01 mm steps.
  double drag = 0, normal = 0, largest_texture = 0;
  int n = 0;
  for (int i = 1; i <= 4500; ++i) {
    const glm::dvec3 f = contact.update_rt({-0.03 + i * 1e-5, 0.0, -d});
    if (i > 500) {
      drag += -f.x, normal += f.z, ++n;
      largest_texture = std::max(largest_texture, std::abs(contact.texture_force_rt().x));
    }
  }
  drag /= n, normal /= n;
  EXPECT_NEAR(normal, k * d, 0.01 * k * d);
  EXPECT_NEAR(drag, mu_k * normal, 0.02 * mu_k * normal);
  EXPECT_GT(largest_texture, 0.9 * p.max_lateral_force_N);
  EXPECT_TRUE(contact.proxy_rt().contact_rt().sliding);
}

}  // namespace
}  // namespace sandpaper::shapes
