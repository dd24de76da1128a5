#pragma once
// Scene files (.hsc), phase 2: tokens -> the syntax of one 3-D scene (objects with materials on
// their surfaces; Minsky 1995, 7.7.1 "haptic texture mapping"). The frame is glTF's: x right, y up,
// z toward the user, lengths with their units. Grammar and codes E08xx: schema/LANGUAGE.md, "Scenes".
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/syntax.hpp"

namespace sandpaper::scenes {

using compiler::Quantity;
using compiler::SourceLocation;

// The six sides of a box, and the way a plane faces, in the scene's frame (y up, z toward the user).
enum class Side { Top, Bottom, Right, Left, Front, Back };  // +y, -y, +x, -x, +z, -z

// material "M" [on SIDE]
struct SurfaceSyntax {
  std::string material;             // library name, one-line expression, or a .hmat path
  SourceLocation material_location;
  std::optional<Side> side;         // a box's face; absent: every surface not given its own
  SourceLocation location;          // the `material` keyword
};

enum class ShapeKind { Sphere, Box, Plane };

struct ObjectSyntax {
  std::string name;
  SourceLocation name_location;
  ShapeKind shape = ShapeKind::Sphere;
  SourceLocation shape_location;
  std::optional<Quantity> radius;               // sphere
  std::optional<Quantity> size[3];              // box: W x H x D (x, y, z); plane: W x D ([0], [2])
  bool inside = false;                          // box: felt from inside (a room)
  Side facing = Side::Top;                      // plane: the side its surface faces
  SourceLocation facing_location;
  Quantity x, y, z;                             // the centre, scene frame
  SourceLocation at_location;                   // spans `X, Y, Z`
  std::vector<SurfaceSyntax> surfaces;          // in file order
  std::optional<Quantity> stiffness;            // N/m: replaces the material's
  std::optional<Quantity> damping;              // N*s/m, along the normal
  std::optional<double> static_friction, kinetic_friction;  // `friction S [K]`: K absent = S
  SourceLocation friction_location;
  std::optional<Quantity> texture_width, texture_height;  // `texture size W [x H]`: metres per unit of u, v
  SourceLocation texture_location;
  std::optional<Quantity> relief_depth;         // `texture relief D [only]`: carve depth (m), normal-force texture
  bool relief_only = false;                     // `only`: no lateral-force texture beside the relief
  SourceLocation relief_location;
  SourceLocation location;                      // the `object` keyword
};

struct SceneSyntax {
  std::shared_ptr<const compiler::SourceFile> file;
  std::string name;
  SourceLocation name_location;
  std::vector<ObjectSyntax> objects;  // in file order
};

// Objects in one scene file: far above a hand-written scene, and a bound on what one file can ask the
// scene compiler to mesh (E0809; docs/RELIABILITY.md, "Limits").
inline constexpr std::size_t kMaxSceneObjects = 1024;

// Whether `path` names a scene file (extension .hsc).
bool is_scene_path(const std::string& path);

// Tokens must come from compiler::lex(..., LexOptions{.commas = true}). Reports E08xx and the unit
// errors E0203-E0205 into `diags`, recovers at the next line, and returns what it could read.
SceneSyntax parse_scene(const std::vector<compiler::Token>& tokens, std::shared_ptr<const compiler::SourceFile> file,
                        compiler::Diagnostics& diags);

const char* side_name(Side side);  // "top", "bottom", "right", "left", "front", "back"

}  // namespace sandpaper::scenes
