#pragma once
// A compiled scene played on the simulated 3-DOF device (sim3d) by its scripted hand, as
// `sandpaper run SCENE --device sim3d` and `sandpaper-play SCENE.sp3 --device sim3d` play it:
// scene_strokes' path, open_sim3d's hand, run_scene_servo's run and check (docs/SHAPES.md).
#include "sandpaper/shapes/scene_program.hpp"
#include "sandpaper/shapes/scene_servo.hpp"
#include "sandpaper/shapes/scene_strokes.hpp"

namespace sandpaper::shapes {

struct ScenePlay {
  SceneStrokePath strokes;
  SceneServoSummary summary;
};

// rate_hz and seconds as run_scene_servo takes them; speed_m_s along the hand's path. Throws
// std::invalid_argument as scene_strokes, SceneRenderer and run_scene_servo do.
ScenePlay play_scene_on_sim3d(const SceneProgram& scene, double rate_hz, double seconds, double speed_m_s);

}  // namespace sandpaper::shapes
