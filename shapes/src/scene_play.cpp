#include "sandpaper/shapes/scene_play.hpp"

#include <cmath>

#include "sandpaper/shapes/dynamic_hand3.hpp"
#include "sandpaper/shapes/scene_renderer.hpp"

namespace sandpaper::shapes {

ScenePlay play_scene_on_sim3d(const SceneProgram& scene, double rate_hz, double seconds, double speed_m_s) {
  ScenePlay out;
  SceneStrokeOptions options;
  options.speed_m_s = speed_m_s;
  out.strokes = scene_strokes(scene, options);
  // Every tick recorded, so that the hand's run can be judged (judge_hand_run).
  const auto ticks = static_cast<std::size_t>(std::ceil(seconds * rate_hz)) + 16;
  DynamicHand3 hand = open_sim3d(HandPath3(out.strokes.path), ticks);
  SceneRenderer renderer(scene);
  out.summary = run_scene_servo(renderer, hand, rate_hz, seconds);
  return out;
}

}  // namespace sandpaper::shapes
