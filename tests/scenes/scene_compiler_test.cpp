// Scene files compiled into scene programs: geometry placed as written, each surface's material and
// contact from the scene, the material or the default, and what the renderer then gives against
// closed-form figures and the 2-D patch's own forces.
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <glm/geometric.hpp>

#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/scenes/scene_compiler.hpp"
#include "sandpaper/scenes/scene_geometry.hpp"
#include "sandpaper/shapes/scene_renderer.hpp"
#include "test_support.hpp"

namespace sandpaper::scenes {
namespace {

SceneResult compile(const std::string& text) {
  return compile_scene_text(test::shipped_compiler(), text, "<test>.hsc", ".");
}

const shapes::SceneSurface& surface_named(const shapes::SceneProgram& s, const std::string& object, const std::string& side = "") {
  for (const auto& surface : s.surfaces)
    if (surface.object == object && surface.side == side) return surface;
  ADD_FAILURE() << "no surface " << object << " " << side;
  return s.surfaces.front();
}

// The device point still at `device`, the proxy settled.
glm::dvec3 settled_force(shapes::SceneRenderer& r, const glm::dvec3& device) {
  glm::dvec3 f{0.0};
  for (int k = 0; k < 64; ++k) f = r.update_rt(device);
  return f;
}

TEST(SceneCompiler, TheExamplesCompileWithTheirObjectsAndMaterials) {
  for (const char* file : {"examples/3d/textured-sphere.hsc", "examples/3d/material-box.hsc"}) {
    const SceneResult r = compile_scene_file(test::shipped_compiler(), file);
    ASSERT_TRUE(r.ok()) << file << "\n" << compiler::format_diagnostics(r.diagnostics);
    EXPECT_EQ(r.program->objects.size(), 2u) << file;
    EXPECT_NO_THROW(shapes::SceneRenderer{*r.program}) << file;
  }
}

TEST(SceneCompiler, ASphereIsPlacedAndItsTextureKeepsItsScaleAlongTheSurface) {
  const auto r = compile(R"(scene "s" {
    object "ball" sphere radius 40 mm at 10 mm, 50 mm, -20 mm {
      material "corduroy"
    }
  })");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& s = *r.program;
  const glm::dvec3 centre{0.010, 0.050, -0.020};
  for (const auto& v : s.mesh.vertices) ASSERT_NEAR(glm::length(v - centre), 0.040, 1e-12);
  const auto& ball = surface_named(s, "ball");
  ASSERT_GE(ball.program, 0);
  // One circumference per unit of u, half of it per unit of v: the texture's metres are the surface's.
  EXPECT_NEAR(ball.uv_size_m.x, 2 * std::numbers::pi * 0.040, 1e-12);
  EXPECT_NEAR(ball.uv_size_m.y, std::numbers::pi * 0.040, 1e-12);
  EXPECT_EQ(s.programs[ball.program].name, "corduroy");
  // Nothing said: the default stiffness, no damping or friction.
  EXPECT_EQ(ball.contact.stiffness_N_per_m, kDefaultStiffness_N_per_m);
  EXPECT_EQ(r.origins[0].stiffness, "default");
  EXPECT_EQ(ball.contact.static_friction, 0);
}

TEST(SceneCompiler, APressedSphereGivesKDAlongTheRadius) {
  const auto r = compile(R"(scene "s" {
    object "ball" sphere radius 50 mm at 0 mm, 0 mm, 0 mm {
      stiffness 600 N/m
    }
  })");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  shapes::SceneRenderer renderer(*r.program);
  // Straight down onto the top (the pole of the scene's sphere is +y), then 4 mm in.
  const glm::dvec3 dir = glm::normalize(glm::dvec3{0.3, 1.0, 0.2});
  renderer.reset_rt(dir * 0.080);
  for (double d = 0.080; d > 0.046; d -= 0.001) renderer.update_rt(dir * d);
  const glm::dvec3 f = settled_force(renderer, dir * 0.046);
  // The facets sag at most 1.5e-4 r = 7.5 um inside the sphere: 0.19 % of 4 mm.
  EXPECT_NEAR(glm::length(f), 600 * 0.004, 0.01 * 600 * 0.004);
  EXPECT_GT(glm::dot(glm::normalize(f), dir), std::cos(1.0 * std::numbers::pi / 180));
}

TEST(SceneCompiler, EachBoxFaceHasTheMaterialNamedForItsSide) {
  const auto r = compile(R"(scene "s" {
    object "crate" box 100 mm x 60 mm x 80 mm at 0 mm, 30 mm, 0 mm {
      material "denim-twill"
      material "corduroy" on top
      material "silk-satin" on right
    }
  })");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& s = *r.program;
  ASSERT_EQ(s.mesh.triangles.size(), 12u);
  auto material_facing = [&](glm::dvec3 n) {
    for (std::size_t t = 0; t < s.mesh.triangles.size(); ++t) {
      const auto& tri = s.mesh.triangles[t];
      const glm::dvec3 a = s.mesh.vertices[tri[0]], b = s.mesh.vertices[tri[1]], c = s.mesh.vertices[tri[2]];
      if (glm::dot(glm::normalize(glm::cross(b - a, c - a)), n) > 0.999) return s.surfaces[s.mesh.materials[t]].material;
    }
    return std::string("(no face)");
  };
  EXPECT_EQ(material_facing({0, 1, 0}), "corduroy");
  EXPECT_EQ(material_facing({1, 0, 0}), "silk-satin");
  for (glm::dvec3 n : {glm::dvec3{0, -1, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}}) EXPECT_EQ(material_facing(n), "denim-twill");
  // The top face spans x +-50 mm, z +-40 mm at y = 60 mm.
  for (std::size_t t = 0; t < 12; ++t) {
    if (s.surfaces[s.mesh.materials[t]].material != "corduroy") continue;
    for (auto i : s.mesh.triangles[t]) {
      EXPECT_NEAR(s.mesh.vertices[i].y, 0.060, 1e-12);
      EXPECT_NEAR(std::abs(s.mesh.vertices[i].x), 0.050, 1e-12);
      EXPECT_NEAR(std::abs(s.mesh.vertices[i].z), 0.040, 1e-12);
    }
  }
}

// The issue's first check through the scene path: a textured floor gives the 2-D patch's lateral
// forces, patch x along +x and patch y along -z (the glTF export's convention), within 1 %.
TEST(SceneCompiler, AFloorGivesThePatchsLateralForcesAtTwentyPoints) {
  for (const char* material : {"corduroy", "grating period 4 mm orientation 30 deg; roughness 0.5", "sandpaper-p60"}) {
    const auto r = compile(std::string(R"(scene "s" {
      object "floor" plane 80 mm x 80 mm at 0 mm, 0 mm, 0 mm {
        material ")") + material + R"("
        stiffness 1000 N/m
      }
    })");
    ASSERT_TRUE(r.ok()) << material << "\n" << compiler::format_diagnostics(r.diagnostics);
    const auto& s = *r.program;
    const auto& floor = surface_named(s, "floor");
    ASSERT_GE(floor.program, 0);
    schema::PatchProgram wide = s.programs[floor.program];
    wide.size_m[0] = wide.size_m[1] = 1.0;  // the patch's force everywhere the floor is
    runtime::PatchEvaluator patch(wide);
    shapes::SceneRenderer renderer(s);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> at(-0.035, 0.035);
    int checked = 0;
    while (checked < 20) {
      const glm::dvec2 p{at(rng), at(rng)};  // (x, z) on the floor
      runtime::HandState hand;
      hand.position_m = {p.x, -p.y};
      const glm::dvec2 f2 = patch.force_rt(hand, 0);
      if (glm::length(f2) < 0.1 * wide.max_lateral_force_N) continue;
      // Pressed 1 mm in from straight above, so that friction (none here) and the proxy's path play no part.
      renderer.reset_rt({p.x, 0.01, p.y});
      const glm::dvec3 f3 = settled_force(renderer, {p.x, -0.001, p.y});
      const glm::dvec3 lateral = renderer.texture_force_rt();
      EXPECT_NEAR(lateral.x, f2.x, 0.01 * glm::length(f2)) << material << " at " << p.x << ", " << p.y;
      EXPECT_NEAR(-lateral.z, f2.y, 0.01 * glm::length(f2)) << material << " at " << p.x << ", " << p.y;
      EXPECT_NEAR(f3.y, 1000 * 0.001, 0.01) << material;
      ++checked;
    }
  }
}

// The version-2 grating's height (docs/TEXTURES.md; compiler/src/codegen/grating.cpp): a square wave,
// 1 on the hill |u| < hill P / 2 and 0 in the valley, smoothed by a Gaussian of sigma, so
// h(u) = sum_k [Phi((u + hill P / 2 + k P) / sigma) - Phi((u - hill P / 2 + k P) / sigma)].
double grating_height(double u, double period, double hill, double sigma) {
  auto phi = [](double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); };
  double h = 0;
  for (int k = -4; k <= 4; ++k)
    h += phi((u + 0.5 * hill * period + k * period) / sigma) - phi((u - 0.5 * hill * period + k * period) / sigma);
  return h;
}

// `texture relief 0.5 mm only` on a floor of a compiled grating (hill 40 %, smoothing 0.2 mm):
// pressed 1 mm, the normal force at 20 points across a period is k (delta - c) within 1 %, c the
// closed-form height carved D deep: c = D (h(0) - h(u)) / (h(0) - h(P / 2)); and no lateral force
// but the relief's.
TEST(SceneCompiler, AReliefOnAFloorIsTheGratingsHeightCarvedIntoIt) {
  const auto r = compile(R"(scene "s" {
    object "floor" plane 80 mm x 80 mm at 0 mm, 0 mm, 0 mm {
      material "grating period 4 mm hill 40% smoothing 0.2 mm; roughness 0.5"
      stiffness 1000 N/m
      texture relief 0.5 mm only
    }
  })");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& floor = surface_named(*r.program, "floor");
  EXPECT_EQ(floor.relief_depth_m, 0.0005);
  EXPECT_FALSE(floor.lateral_texture);
  shapes::SceneRenderer renderer(*r.program);
  const double P = 0.004, D = 0.0005, k = 1000, press = 0.001, delta = press + shapes::ProxyOptions{}.surface_offset_m;
  const double top = grating_height(0, P, 0.4, 0.0002), bottom = grating_height(P / 2, P, 0.4, 0.0002);
  for (int i = 0; i < 20; ++i) {
    const double u = -P / 2 + P * (i + 0.25) / 20;
    renderer.reset_rt({u, 0.01, 0.005});
    const glm::dvec3 f = settled_force(renderer, {u, -press, 0.005});
    const double c = D * (top - grating_height(u, P, 0.4, 0.0002)) / (top - bottom);
    EXPECT_NEAR(f.y, k * (delta - c), 0.01 * k * (delta - c)) << "u = " << u * 1e3 << " mm";
    EXPECT_EQ(renderer.texture_force_rt(), glm::dvec3{0.0});
    EXPECT_NEAR(f.x, renderer.relief_force_rt().x, 1e-12);
  }
}

// A relief on a surface whose material has no texture, or no material: W0854 at the relief, once
// an object and material, and no relief; the scene still compiles.
TEST(SceneCompiler, AReliefWithNoTextureToFollowIsAWarningAndNoRelief) {
  const auto r = compile(R"(scene "s" {
    object "a" box 20 mm x 20 mm x 20 mm at 0 mm, 0 mm, 0 mm {
      material "spring 300 N/m"
      material "corduroy" on top
      texture relief 0.5 mm
    }
    object "b" sphere radius 20 mm at 100 mm, 0 mm, 0 mm {
      texture relief 0.2 mm only
    }
  })");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  std::vector<std::string> warnings;
  for (const auto& d : r.diagnostics.all())
    if (d.code == "W0854") warnings.push_back(std::to_string(d.location.line) + ": " + d.message);
  ASSERT_EQ(warnings.size(), 2u) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NE(warnings[0].find("5: the relief on object \"a\""), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("\"spring 300 N/m\" has no texture"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("8: the relief on object \"b\" has nothing to follow: it has no material"), std::string::npos)
      << warnings[1];
  EXPECT_EQ(surface_named(*r.program, "a", "top").relief_depth_m, 0.0005);
  EXPECT_TRUE(surface_named(*r.program, "a", "top").lateral_texture);
  EXPECT_EQ(surface_named(*r.program, "a").relief_depth_m, 0.0);  // the faces but the top
  EXPECT_EQ(surface_named(*r.program, "b").relief_depth_m, 0.0);
  shapes::SceneRenderer renderer(*r.program);  // and it can be felt
}

TEST(SceneCompiler, ContactComesFromTheSceneElseTheMaterialElseTheDefault) {
  const auto r = compile(R"(scene "s" {
    object "a" sphere radius 20 mm at 0 mm, 0 mm, 0 mm {
      material "spring 300 N/m; damper 2 N*s/m; physics Friction static 0.6 kinetic 0.4 press 1 N"
    }
    object "b" sphere radius 20 mm at 100 mm, 0 mm, 0 mm {
      material "spring 300 N/m; damper 2 N*s/m; physics Friction static 0.6 kinetic 0.4 press 1 N"
      stiffness 900 N/m
      friction 0.3
    }
  })");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const auto& a = surface_named(*r.program, "a");
  const auto& b = surface_named(*r.program, "b");
  EXPECT_EQ(a.contact.stiffness_N_per_m, 300);
  EXPECT_EQ(a.contact.damping_Ns_per_m, 2);
  EXPECT_EQ(a.contact.static_friction, 0.6);
  EXPECT_EQ(a.contact.kinetic_friction, 0.4);
  EXPECT_EQ(r.origins[0].stiffness, "material");
  EXPECT_EQ(r.origins[0].friction, "material");
  EXPECT_EQ(b.contact.stiffness_N_per_m, 900);
  EXPECT_EQ(b.contact.damping_Ns_per_m, 2);
  EXPECT_EQ(b.contact.static_friction, 0.3);
  EXPECT_EQ(b.contact.kinetic_friction, 0.3);
  EXPECT_EQ(r.origins[1].stiffness, "scene");
  EXPECT_EQ(r.origins[1].damping, "material");
  EXPECT_EQ(a.program, -1);  // no texture
  // One material text, compiled once for both.
  ASSERT_EQ(r.materials.size(), 1u);
  EXPECT_EQ(r.materials[0].surfaces.size(), 2u);
}

TEST(SceneCompiler, LawsAShapeDoesNotCarryAreNamedInAWarning) {
  const auto r = compile(R"(scene "s" {
    object "a" sphere radius 20 mm at 0 mm, 0 mm, 0 mm {
      material "like corduroy; force AntiViscous damping 1 N*s/m"
    }
  })");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  bool warned = false;
  for (const auto& d : r.diagnostics.all())
    if (d.code == "W0851") {
      warned = true;
      EXPECT_NE(d.message.find("damper"), std::string::npos) << d.message;
    }
  EXPECT_TRUE(warned);
}

TEST(SceneCompiler, AMaterialsErrorIsReportedAtItsUseAndGivesNoProgram) {
  const auto r = compile(R"(scene "s" {
    object "a" sphere radius 20 mm at 0 mm, 0 mm, 0 mm {
      material "no-such-entry"
    }
  })");
  EXPECT_FALSE(r.ok());
  EXPECT_FALSE(r.program);
  bool noted = false;
  for (const auto& d : r.diagnostics.all())
    if (d.code == "E0301")
      for (const auto& n : d.notes) noted = noted || n.message.find("object \"a\"") != std::string::npos;
  EXPECT_TRUE(noted) << compiler::format_diagnostics(r.diagnostics);
}

TEST(SceneCompiler, AMissingFileIsE0800) {
  const auto r = compile_scene_file(test::shipped_compiler(), "no/such/scene.hsc");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics.all().front().code, "E0800");
}

// An empty scene compiles, with W0852 saying how to add an object in the scene file's own words.
TEST(SceneCompiler, AnEmptySceneWarnsHowToAddAnObject) {
  const auto r = compile("scene \"empty\" {\n}\n");
  ASSERT_TRUE(r.ok()) << compiler::format_diagnostics(r.diagnostics);
  const compiler::Diagnostic* w = nullptr;
  for (const auto& d : r.diagnostics.all())
    if (d.code == "W0852") w = &d;
  ASSERT_NE(w, nullptr) << compiler::format_diagnostics(r.diagnostics);
  EXPECT_NE(w->suggestion.find("object \"NAME\" sphere radius R"), std::string::npos) << w->suggestion;
}

}  // namespace
}  // namespace sandpaper::scenes
