#pragma once
// Where `sandpaper run SCENE --device sim3d` sends the simulated hand: onto each object in turn,
// pressing into the surface it shows from above and stroking across it, then up over the scene to
// the next (the thesis' scripted strokes, 3-D; docs/SHAPES.md, "Running a scene").
#include <string>
#include <vector>

#include "sandpaper/shapes/hand_path3.hpp"
#include "sandpaper/shapes/scene_program.hpp"

namespace sandpaper::shapes {

struct SceneStrokeOptions {
  double depth_m = 0.003;    // aimed below the surface; the handle stops where the springs balance
  double stroke_m = 0.04;    // across the surface, centred on the point pressed
  double lift_m = 0.01;      // above the surface before coming down and after lifting off
  double speed_m_s = 0.05;   // along the whole path
};

// One object's stroke: where it was pressed (m) and the surface's outward normal there.
struct SceneStroke {
  std::string object;
  glm::dvec3 point_m{0.0};
  glm::dvec3 normal{0.0, 1.0, 0.0};
};

struct SceneStrokePath {
  HandPath3Spec path;
  std::vector<SceneStroke> strokes;       // in path order
  std::vector<std::string> not_reached;   // objects no vertical line from above meets first
};

// For each object, the first surface a vertical line from above meets at its footprint's centre,
// else at the centres of its quarters, when that surface is the object's and faces up (normal y >
// 0.5); the stroke runs along x. Throws std::invalid_argument when no object can be reached, and
// what Mesh::build_nonrt throws.
SceneStrokePath scene_strokes(const SceneProgram& scene, const SceneStrokeOptions& options = {});

}  // namespace sandpaper::shapes
