#pragma once
// The open scene (.hsc) in the studio: compiled by the scenes room (scenes::compile_scene_text),
// drawn by the page's 3-D view from geometry(), and felt in the 3-D Dummy mode by touch(): the page
// posts a simulated device point, the scene's contact renderer (shapes::SceneRenderer) settles its
// proxy there, and the force is read back (docs/STUDIO.md, "Scenes in 3-D").
//
// A simulated device has no servo thread: the renderer is updated on the request's thread, under
// this object's own mutex, as `sandpaper probe` updates it. Nothing here touches the live loop, which
// plays 2-D programs on the 2-axis joystick.
//
// Built without SANDPAPER_SHAPES, built() is false and compile() refuses (scene_view_unbuilt.cpp):
// this header names no shapes type, so the session compiles either way.
#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/diagnostic.hpp"

namespace sandpaper::studio {

class SceneView {
 public:
  using Point_m = std::array<double, 3>;  // the scene's frame: x right, y up, z toward the user (glTF), metres

  // What opening or editing a scene answers: `answer` is {"ok", "diagnostics", and when ok "scene":
  // {"scene", "device", "objects", "triangles", "surfaces"}}; `view` is set when the scene compiled
  // and its renderer could be built.
  struct Compiled {
    nlohmann::json answer;
    compiler::Diagnostics diagnostics;  // as in `answer`, for marking where another file's came in
    std::shared_ptr<SceneView> view;
  };

  // Whether this studio was built with the shapes room (SANDPAPER_SHAPES).
  static bool built() noexcept;
  // The message for a scene in a studio built without it.
  static std::string unbuilt_message();
  // Compiles `text` as the scene file `name` (its .hmat paths relative to `base_dir`), for the
  // compiler's device. Throws RequestError 501 when !built().
  static Compiled compile(const compiler::Compiler& compiler, const std::string& text, const std::string& name,
                          const std::filesystem::path& base_dir);

  ~SceneView();
  SceneView(const SceneView&) = delete;
  SceneView& operator=(const SceneView&) = delete;

  // For drawing: {"scene", "device", "frame", "positions_m" (x, y, z per vertex, flat), "triangles"
  // (three vertex indices each, flat, counter-clockwise seen from outside), "triangle_surfaces" (one
  // surface index per triangle), "surfaces": [{"index", "object", "side", "material",
  // "material_name", "colour" ("#rrggbb"), "stiffness_N_per_m", "damping_Ns_per_m",
  // "static_friction", "kinetic_friction", "textured", "compiled_max_lateral_force_N"}], "objects":
  // [{"name", "shape", "first_triangle", "triangle_count"}], "bounds_m": {"min", "max"}, "touch":
  // the last touch()}.
  nlohmann::json geometry() const;

  // The 3-D Dummy mode: the simulated device moves to `device_m`. With `from_m`, a new touch: the
  // proxy is first put there, out of contact (the hand lifted and put down, as `sandpaper probe
  // --from` starts); without it the proxy follows from where it is (a drag, friction and all). The
  // proxy is then settled with the device held still: updated until it stops moving, at most
  // kSettleUpdates times. Returns {"device_m", "proxy_m", "force_N" (on the device), "force_magnitude_N",
  // "texture_force_N", "in_contact", "surface" (index or null), "object", "side", "material",
  // "normal", "normal_force_N", "sliding", "constraints", "settle_updates", "moves"}. RequestError 400
  // for a point farther than kReach_m beyond the scene's bounds.
  nlohmann::json touch(const Point_m& device_m, const std::optional<Point_m>& from_m);
  // The last touch()'s answer (before any: the device at rest above the scene, free).
  nlohmann::json last_touch() const;

  // A probe holds the device still at each point: one update can end before the proxy reaches its
  // place (the renderer bounds its work a tick), so it is updated until it stops, as
  // `sandpaper probe` does (apps/sandpaper/cmd_probe.cpp).
  static constexpr int kSettleUpdates = 64;
  // How far beyond the scene's bounding box a device point may be posted (m): a mouse far off the
  // scene is a mistake, not a place to feel.
  static constexpr double kReach_m = 1.0;

 private:
  struct Impl;
  explicit SceneView(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace sandpaper::studio
