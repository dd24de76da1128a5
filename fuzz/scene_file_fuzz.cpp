// Scene text (.hsc, schema/LANGUAGE.md "Scenes") through the material lexer and the scene parser:
// the diagnostics as printed and as JSON, each inside the text it points into; every object kept
// is one the grammar allows with values in range (an error drops its statement, never leaves half of
// it); and a scene read without errors, written back as text, reads again without errors to the same
// syntax (the parser takes what its own grammar says it takes). Bad input is a diagnostic; nothing is
// caught here.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "fuzz_support.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/scenes/scene_parser.hpp"

namespace {

using namespace sandpaper;
using scenes::ObjectSyntax;
using scenes::SceneSyntax;
using scenes::ShapeKind;

SceneSyntax parse(const std::string& name, const std::string& text, compiler::Diagnostics& diags) {
  auto file = std::make_shared<const compiler::SourceFile>(name, text);
  const auto tokens = compiler::lex(file, diags, compiler::LexOptions{.commas = true});
  return scenes::parse_scene(tokens, file, diags);
}

// The material language's bound on a quantity in SI units (E0103).
bool in_bounds(double si) { return std::isfinite(si) && (si == 0 || (std::abs(si) >= 1e-12 && std::abs(si) <= 1e12)); }
bool positive(const std::optional<compiler::Quantity>& q) { return q && in_bounds(q->si) && q->si > 0; }

void check_object(const ObjectSyntax& o) {
  const std::string who = "object \"" + o.name + "\": ";
  fuzz::check(o.name.find_first_not_of(" \t") != std::string::npos, who + "kept with an empty name");
  fuzz::check(in_bounds(o.x.si) && in_bounds(o.y.si) && in_bounds(o.z.si), who + "a centre out of bounds");
  switch (o.shape) {
    case ShapeKind::Sphere:
      fuzz::check(positive(o.radius) && !o.size[0] && !o.size[1] && !o.size[2], who + "a sphere's sizes");
      break;
    case ShapeKind::Box:
      fuzz::check(!o.radius && positive(o.size[0]) && positive(o.size[1]) && positive(o.size[2]), who + "a box's sizes");
      break;
    case ShapeKind::Plane:
      fuzz::check(!o.radius && positive(o.size[0]) && !o.size[1] && positive(o.size[2]), who + "a plane's sizes");
      break;
  }
  fuzz::check(!o.inside || o.shape == ShapeKind::Box, who + "`inside` on a shape that is not a box");
  fuzz::check(o.facing == scenes::Side::Top || o.shape == ShapeKind::Plane, who + "a facing on a shape that is not a plane");
  std::set<int> sides;
  for (const auto& s : o.surfaces) {
    fuzz::check(s.material.find_first_not_of(" \t") != std::string::npos, who + "an empty material kept");
    fuzz::check(!s.side || o.shape == ShapeKind::Box, who + "a side on a shape that is not a box");
    fuzz::check(sides.insert(s.side ? static_cast<int>(*s.side) : -1).second, who + "two materials for one side");
  }
  fuzz::check(!o.stiffness || positive(o.stiffness), who + "a stiffness kept that is not positive");
  fuzz::check(!o.damping || (in_bounds(o.damping->si) && o.damping->si >= 0), who + "a negative damping kept");
  fuzz::check(o.static_friction.has_value() == o.kinetic_friction.has_value(), who + "half a friction");
  if (o.static_friction)
    fuzz::check(in_bounds(*o.static_friction) && in_bounds(*o.kinetic_friction) && *o.kinetic_friction >= 0 &&
                    *o.kinetic_friction <= *o.static_friction,
                who + "friction out of range");
  fuzz::check(!o.texture_width || positive(o.texture_width), who + "a texture width kept that is not positive");
  fuzz::check(!o.texture_height || (o.texture_width && positive(o.texture_height)), who + "a texture height kept without a positive width");
  fuzz::check(!o.relief_depth || (positive(o.relief_depth) && o.relief_depth->si <= 0.01), who + "a relief depth kept out of (0, 10 mm]");
  fuzz::check(!o.relief_only || o.relief_depth, who + "`only` kept without a relief");
}

// A number as the lexer reads it back to the same double.
std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}
std::string quantity(const compiler::Quantity& q) { return number(q.value) + " " + q.unit; }
std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

// The scene as text in the grammar's canonical form.
std::string write(const SceneSyntax& scene) {
  std::string t = "scene " + quoted(scene.name) + " {\n";
  for (const auto& o : scene.objects) {
    t += "object " + quoted(o.name) + " ";
    switch (o.shape) {
      case ShapeKind::Sphere: t += "sphere radius " + quantity(*o.radius); break;
      case ShapeKind::Box:
        t += "box " + quantity(*o.size[0]) + " x " + quantity(*o.size[1]) + " x " + quantity(*o.size[2]);
        if (o.inside) t += " inside";
        break;
      case ShapeKind::Plane:
        t += "plane " + quantity(*o.size[0]) + " x " + quantity(*o.size[2]) + " facing " + scenes::side_name(o.facing);
        break;
    }
    t += " at " + quantity(o.x) + ", " + quantity(o.y) + ", " + quantity(o.z) + " {\n";
    for (const auto& s : o.surfaces)
      t += "material " + quoted(s.material) + (s.side ? std::string(" on ") + scenes::side_name(*s.side) : "") + "\n";
    if (o.stiffness) t += "stiffness " + quantity(*o.stiffness) + "\n";
    if (o.damping) t += "damping " + quantity(*o.damping) + "\n";
    if (o.static_friction) t += "friction " + number(*o.static_friction) + " " + number(*o.kinetic_friction) + "\n";
    if (o.texture_width)
      t += "texture size " + quantity(*o.texture_width) + (o.texture_height ? " x " + quantity(*o.texture_height) : "") + "\n";
    if (o.relief_depth) t += "texture relief " + quantity(*o.relief_depth) + (o.relief_only ? " only" : "") + "\n";
    t += "}\n";
  }
  return t + "}\n";
}

bool same(const std::optional<compiler::Quantity>& a, const std::optional<compiler::Quantity>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->value == b->value && a->unit == b->unit && a->si == b->si);
}
bool same(const compiler::Quantity& a, const compiler::Quantity& b) {
  return a.value == b.value && a.unit == b.unit && a.si == b.si;
}

bool same(const ObjectSyntax& a, const ObjectSyntax& b) {
  if (a.name != b.name || a.shape != b.shape || !same(a.radius, b.radius) || a.inside != b.inside ||
      a.facing != b.facing || !same(a.x, b.x) || !same(a.y, b.y) || !same(a.z, b.z) || !same(a.stiffness, b.stiffness) ||
      !same(a.damping, b.damping) || a.static_friction != b.static_friction || a.kinetic_friction != b.kinetic_friction ||
      !same(a.texture_width, b.texture_width) || !same(a.texture_height, b.texture_height) ||
      !same(a.relief_depth, b.relief_depth) || a.relief_only != b.relief_only || a.surfaces.size() != b.surfaces.size())
    return false;
  for (int i = 0; i < 3; ++i)
    if (!same(a.size[i], b.size[i])) return false;
  for (std::size_t i = 0; i < a.surfaces.size(); ++i)
    if (a.surfaces[i].material != b.surfaces[i].material || a.surfaces[i].side != b.surfaces[i].side) return false;
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  compiler::Diagnostics diags;
  const SceneSyntax scene = parse("<fuzz>.hsc", text, diags);
  (void)compiler::format_diagnostics(diags);
  fuzz::dump_json(compiler::diagnostics_json(diags));

  // Every diagnostic points into the text (a line of it, or the line after a final newline); the one
  // about the whole file's size (E0105) at line 0.
  const auto lines = static_cast<int>(scene.file->line_starts.size());
  for (const auto& d : diags.all()) {
    if (d.code == "E0009" || d.code == "E0105") continue;
    fuzz::check(d.location.file && d.location.line >= 1 && d.location.line <= lines && d.location.column >= 1,
                d.code + " at " + d.location.str() + ", outside the text");
  }

  fuzz::check(scene.objects.size() <= scenes::kMaxSceneObjects, "more objects kept than the limit");
  for (const auto& o : scene.objects) check_object(o);
  if (diags.has_errors()) return 0;

  std::set<std::string> names;
  for (const auto& o : scene.objects) fuzz::check(names.insert(o.name).second, "two objects named \"" + o.name + "\" without an error");

  // What the parser took, written in its grammar, it takes again to the same scene.
  const std::string again_text = write(scene);
  compiler::Diagnostics again_diags;
  const SceneSyntax again = parse("<again>.hsc", again_text, again_diags);
  fuzz::check(!again_diags.has_errors(), "a scene written back does not read:\n" + compiler::format_diagnostics(again_diags) +
                                             "\n" + again_text);
  fuzz::check(again.name == scene.name && again.objects.size() == scene.objects.size(), "a scene written back reads otherwise");
  for (std::size_t i = 0; i < scene.objects.size(); ++i)
    fuzz::check(same(scene.objects[i], again.objects[i]), "object " + std::to_string(i + 1) + " written back reads otherwise");
  return 0;
}
