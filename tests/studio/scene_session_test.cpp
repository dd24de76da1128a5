// A scene (.hsc) in the studio's session (docs/STUDIO.md, "Scenes in 3-D"): opened beside a playing
// material, compiled by the scenes room, touched by the 3-D Dummy mode's simulated device (the force
// is the spring of the press depth, k d, worked by hand from the scene's own numbers), and kept while
// an edit does not compile. Built without the shapes room, opening a scene says so and changes nothing.
#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "sandpaper/runtime/dummy_joystick.hpp"
#include "sandpaper/runtime/sim_joystick.hpp"
#include "sandpaper/studio/session.hpp"
#include "test_support.hpp"

namespace sandpaper {
namespace {
namespace fs = std::filesystem;

// A ball of radius 40 mm on y = 40 mm, 800 N/m, no friction and no texture: the force at a press of
// d along the radius is k d along it.
constexpr const char* kBall =
    "scene \"ball\" {\n"
    "  object \"ball\" sphere radius 40 mm at 0 mm, 40 mm, 0 mm {\n"
    "    stiffness 800 N/m\n"
    "  }\n"
    "}\n";

struct SceneSession {
  fs::path root = test::temp_dir("studio-scene");
  std::unique_ptr<studio::LiveLoop> loop;
  std::unique_ptr<studio::Session> session;

  SceneSession() {
    auto d = std::make_unique<runtime::DummyJoystick>(runtime::sim_device_limits());
    auto* dummy = d.get();
    loop = std::make_unique<studio::LiveLoop>(std::move(d), dummy, studio::LoopOptions{});
    session = std::make_unique<studio::Session>(test::shipped_compiler(), *loop, root, root / ".previews");
    loop->start_nonrt();
    std::ofstream(root / "m.hmat") << "roughness 0.5\ngrating period 3 mm\n";
    std::ofstream(root / "ball.hsc") << kBall;
  }
  ~SceneSession() { loop->stop_nonrt(); }
};

int status_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const studio::RequestError& e) {
    return e.status;
  }
  return 0;
}

#if SANDPAPER_STUDIO_WITH_SCENES

TEST(StudioScene, ATouchIsTheSpringOfItsPressAndTheJoystickKeepsItsMaterial) {
  SceneSession s;
  const auto material = s.session->open("m.hmat");
  ASSERT_TRUE(material["ok"].get<bool>());
  EXPECT_EQ(status_of([&] { s.session->scene(); }), 409);  // a material has no scene

  const auto opened = s.session->open("ball.hsc");
  ASSERT_TRUE(opened["ok"].get<bool>()) << opened.dump(2);
  EXPECT_EQ(opened["version"], material["version"]);  // nothing offered to the 2-axis joystick
  EXPECT_EQ(s.session->current()["kind"], "scene");
  EXPECT_TRUE(s.session->current()["parameters"].empty());

  const auto g = s.session->scene();
  const auto triangles = g["triangle_surfaces"].size();
  ASSERT_GT(triangles, 1000u);
  EXPECT_EQ(g["triangles"].size(), 3 * triangles);
  EXPECT_EQ(g["positions_m"].size() % 3, 0u);
  EXPECT_EQ(g["surfaces"][0]["stiffness_N_per_m"], 800.0);
  EXPECT_NEAR(g["bounds_m"]["max"][1].get<double>(), 0.080, 1e-9);
  EXPECT_FALSE(g["touch"]["in_contact"].get<bool>());  // the device waits above the scene

  // Pressed 2 mm in at the top, then dragged over the ball at that depth: k d = 1.6 N along the
  // radius each time (the proxy's 1 um above the surface and the facets' sag are well under 1 %).
  const double k = 800, d = 0.002, r = 0.040;
  const auto top = s.session->scene_touch({0, 0.040 + r - d, 0}, studio::SceneView::Point_m{0, 0.1, 0});
  ASSERT_TRUE(top["in_contact"].get<bool>()) << top.dump(2);
  EXPECT_NEAR(top["force_magnitude_N"].get<double>(), k * d, 0.01 * k * d);
  EXPECT_NEAR(top["force_N"][1].get<double>(), k * d, 0.01 * k * d);
  EXPECT_EQ(top["object"], "ball");
  for (int i = 1; i <= 10; ++i) {
    const double a = 0.05 * i;  // radians from the top, toward +x
    const studio::SceneView::Point_m p{(r - d) * std::sin(a), 0.040 + (r - d) * std::cos(a), 0};
    const auto t = s.session->scene_touch(p, std::nullopt);
    ASSERT_TRUE(t["in_contact"].get<bool>()) << "at " << a << " rad: " << t.dump(2);
    EXPECT_NEAR(t["normal_force_N"].get<double>(), k * d, 0.01 * k * d) << "at " << a << " rad";
    EXPECT_NEAR(t["device_m"][0].get<double>(), p[0], 1e-12);
  }
  EXPECT_EQ(s.session->scene_device()["moves"], 11);

  EXPECT_EQ(status_of([&] { s.session->scene_touch({0, 50, 0}, std::nullopt); }), 400);  // far off the scene
  EXPECT_EQ(status_of([&] { s.session->render_view("height", std::array{0.0, 0.0}.data(), std::array{1.0, 1.0}.data()); }), 409);
}

// A relief (a normal-force texture): across one period of a 6 mm grating carved 0.5 mm deep, the
// carve under the proxy runs from the hills (0) to the valleys (0.5 mm), and the felt normal force
// is the spring pressed into the carved surface, k (d - c), with the relief's share k min(d, c).
TEST(StudioScene, ATouchOnAReliefGivesItsCarveAndItsShare) {
  SceneSession s;
  std::ofstream(s.root / "relief.hsc") << "scene \"r\" {\n"
                                          "  object \"floor\" plane 100 mm x 100 mm at 0 mm, 0 mm, 0 mm {\n"
                                          "    material \"grating period 6 mm; roughness 0.4\"\n"
                                          "    stiffness 1000 N/m\n"
                                          "    texture relief 0.5 mm only\n"
                                          "  }\n"
                                          "}\n";
  ASSERT_TRUE(s.session->open("relief.hsc")["ok"].get<bool>());
  const double k = 1000, d = 0.001;
  double lo = 1, hi = -1;
  for (int i = 0; i <= 60; ++i) {
    const double x = 0.0001 * i;  // 6 mm in 0.1 mm steps
    const auto t = s.session->scene_touch({x, -d, 0.0}, studio::SceneView::Point_m{x, 0.01, 0.0});
    ASSERT_TRUE(t["in_contact"].get<bool>()) << t.dump(2);
    ASSERT_TRUE(t["relief_carve_m"].is_number()) << t.dump(2);
    const double c = t["relief_carve_m"].get<double>();
    lo = std::min(lo, c);
    hi = std::max(hi, c);
    EXPECT_NEAR(t["normal_force_N"].get<double>(), k * d, 0.01 * k * d);  // the mesh surface's press
    EXPECT_NEAR(t["relief_force_N"][1].get<double>(), -k * std::min(d, c), 1e-3) << "at x = " << x;
    EXPECT_NEAR(t["force_N"][1].get<double>(), k * std::max(0.0, d - c), 0.01 * k * d) << "at x = " << x;
  }
  EXPECT_NEAR(lo, 0.0, 0.02e-3);
  EXPECT_NEAR(hi, 0.5e-3, 0.02e-3);
  // Without a relief the carve is null and the share zero.
  ASSERT_TRUE(s.session->open("ball.hsc")["ok"].get<bool>());
  const auto top = s.session->scene_touch({0, 0.078, 0}, studio::SceneView::Point_m{0, 0.1, 0});
  EXPECT_TRUE(top["relief_carve_m"].is_null());
  EXPECT_EQ(top["relief_force_N"], nlohmann::json::array({0.0, 0.0, 0.0}));
}

TEST(StudioScene, AnEditThatDoesNotCompileKeepsTheLastGoodScene) {
  SceneSession s;
  ASSERT_TRUE(s.session->open("ball.hsc")["ok"].get<bool>());
  const auto v = s.session->current()["scene_version"].get<std::uint64_t>();
  std::string broken = kBall;
  broken.replace(broken.find("800 N/m"), 7, "800 N/mm2");
  const auto r = s.session->update(broken);
  EXPECT_FALSE(r["ok"].get<bool>());
  ASSERT_FALSE(r["diagnostics"].empty());
  EXPECT_EQ(r["diagnostics"][0]["line"], 3);
  EXPECT_EQ(r["scene_version"].get<std::uint64_t>(), v);
  const auto t = s.session->scene_touch({0, 0.078, 0}, studio::SceneView::Point_m{0, 0.1, 0});
  EXPECT_NEAR(t["force_magnitude_N"].get<double>(), 1.6, 0.016);  // the last good ball, still felt

  std::string stiffer = kBall;
  stiffer.replace(stiffer.find("800 N/m"), 7, "1600 N/m");
  ASSERT_TRUE(s.session->update(stiffer)["ok"].get<bool>());
  EXPECT_GT(s.session->current()["scene_version"].get<std::uint64_t>(), v);
  const auto t2 = s.session->scene_touch({0, 0.078, 0}, studio::SceneView::Point_m{0, 0.1, 0});
  EXPECT_NEAR(t2["force_magnitude_N"].get<double>(), 3.2, 0.032);
}

TEST(StudioScene, NewMakesASceneThatCompiles) {
  SceneSession s;
  const auto created = s.session->create("desk.hsc");
  EXPECT_TRUE(created["ok"].get<bool>()) << created.dump(2);
  EXPECT_EQ(s.session->current()["kind"], "scene");
  EXPECT_EQ(status_of([&] { s.session->save_as("desk.hmat"); }), 400);  // a scene stays a .hsc
}

#else

TEST(StudioScene, AStudioWithoutShapesSaysSoAndKeepsItsFile) {
  SceneSession s;
  ASSERT_TRUE(s.session->open("m.hmat")["ok"].get<bool>());
  try {
    s.session->open("ball.hsc");
    ADD_FAILURE() << "a scene opened in a studio built without the shapes room";
  } catch (const studio::RequestError& e) {
    EXPECT_EQ(e.status, 501);
    EXPECT_NE(std::string(e.what()).find("built without SANDPAPER_SHAPES"), std::string::npos) << e.what();
  }
  EXPECT_EQ(s.session->current()["file"], "m.hmat");
  EXPECT_EQ(status_of([&] { s.session->scene(); }), 501);
}

#endif

}  // namespace
}  // namespace sandpaper
