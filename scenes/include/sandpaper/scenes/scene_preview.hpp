#pragma once
// A picture of a compiled scene, as `sandpaper preview SCENE -o DIR` writes it: an orthographic view
// from the front, right and above, each surface in its own colour, shaded by its facing to a light,
// and each textured surface's lateral-force magnitude (its texture through the UVs, at the surface)
// drawn as brightness, so the ribs of a grating and the grains of a photograph show where they lie.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "sandpaper/shapes/scene_program.hpp"

namespace sandpaper::scenes {

struct ScenePicture {
  int width = 0, height = 0;              // px
  std::vector<std::uint8_t> rgb;          // width * height * 3, row 0 at the top
  double pixel_m = 0;                     // metres of the scene per pixel (orthographic)
  glm::dvec3 view_from{0.0};              // unit direction toward the viewer
  std::vector<std::array<std::uint8_t, 3>> surface_colours;  // per surface of the scene
  std::size_t pixels_on_surfaces = 0;
};

// max_side: the picture's longer side, px (16 to 4096). Throws std::invalid_argument for an empty
// scene or a side out of range, and what SceneRenderer throws for a scene it cannot feel.
ScenePicture render_scene_picture(const shapes::SceneProgram& scene, int max_side);

}  // namespace sandpaper::scenes
