#pragma once
// The shapes a scene file names, as triangles in the scene's frame (m; x right, y up, z toward the
// user). Each face's UVs are laid so that a texture keeps its own scale and reads as on a patch
// exported to glTF (docs/GLTF.md): patch x along the face's first axis, patch y along the normal
// crossed with it; on a horizontal face facing up, patch x is +x and patch y is -z.
#include <cstdint>

#include <glm/vec3.hpp>

#include "sandpaper/scenes/scene_compiler.hpp"
#include "sandpaper/scenes/scene_parser.hpp"

namespace sandpaper::scenes {

// Longitude segments and latitude bands of a scene's sphere: its facets sag at most
// r (1 - cos(pi / 256) cos(pi / 256)) = 1.5e-4 r inside it (7.5 um on a 50 mm ball), and a facet's
// normal is within 0.7 degrees of the radius through it; 65,280 triangles.
inline constexpr std::uint32_t kSphereSegments = 256, kSphereBands = 128;

// The outward unit normal of a side, and the first of its two face axes (patch x).
glm::dvec3 side_normal(Side side);
glm::dvec3 side_first_axis(Side side);

// The object's triangles and one surface per material statement (by side for a box: the faces a
// `material ... on SIDE` names get that surface, the rest the one without a side, or a surface with
// no material). Sizes come from the syntax in SI; the parser has checked they are there.
ObjectSource object_source(const ObjectSyntax& object);

}  // namespace sandpaper::scenes
