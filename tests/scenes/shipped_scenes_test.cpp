// Every shipped 3-D example (scene files and glTF scenes), played by the simulated 3-DOF hand as `sandpaper run SCENE --device
// sim3d` plays it: 10 s at 1 kHz with no energy gained and no instability (shapes/scene_servo.hpp
// defines both), and every object stroked.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "sandpaper/scenes/gltf_scene.hpp"
#include "sandpaper/scenes/scene_compiler.hpp"
#include "sandpaper/shapes/dynamic_hand3.hpp"
#include "sandpaper/shapes/scene_renderer.hpp"
#include "sandpaper/shapes/scene_servo.hpp"
#include "sandpaper/shapes/scene_strokes.hpp"
#include "test_support.hpp"

namespace sandpaper::scenes {
namespace {

std::vector<std::filesystem::path> shipped_scenes() {
  std::vector<std::filesystem::path> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator("examples/3d"))
    if (e.path().extension() == ".hsc" || e.path().extension() == ".gltf" || e.path().extension() == ".glb") out.push_back(e.path());
  return out;
}

TEST(ShippedScenes, TheDynamicHandOnEachForTenSecondsGainsNoEnergyAndStaysStable) {
  const auto files = shipped_scenes();
  ASSERT_GE(files.size(), 3u);
  for (const auto& file : files) {
    const bool gltf = file.extension() != ".hsc";
    const SceneResult r = gltf ? compile_gltf_scene(test::shipped_compiler(), file) : compile_scene_file(test::shipped_compiler(), file);
    ASSERT_TRUE(r.ok()) << file << "\n" << compiler::format_diagnostics(r.diagnostics);
    const shapes::SceneStrokePath strokes = shapes::scene_strokes(*r.program);
    EXPECT_TRUE(strokes.not_reached.empty()) << file << ": " << strokes.not_reached.front();
    shapes::DynamicHand3 hand = shapes::open_sim3d(shapes::HandPath3(strokes.path), 10016);
    shapes::SceneRenderer renderer(*r.program);
    const auto s = shapes::run_scene_servo(renderer, hand, 1000.0, 10.0);
    EXPECT_EQ(s.stop, shapes::SceneStop::Completed) << file;
    EXPECT_EQ(s.ticks, 10000u) << file;
    // Each object pressed on for a while: the hand is in contact for at least a tenth of the run.
    EXPECT_GT(s.ticks_in_contact, s.ticks / 10) << file;
    EXPECT_TRUE(s.energy.no_energy_gained()) << file << ": gained " << s.energy.energy_gained_J << " J";
    ASSERT_TRUE(s.hand) << file;
    EXPECT_TRUE(s.hand->active_paid) << file;
    EXPECT_TRUE(s.hand->stable()) << file << ": peak " << s.peak_force_N << " N, excursion " << s.hand->max_excursion_m;
    EXPECT_TRUE(s.passed()) << file;
  }
}

}  // namespace
}  // namespace sandpaper::scenes
