// Scene files (.hsc) into their syntax: every form of schema/LANGUAGE.md's "Scenes" grammar read in
// SI units, each error code at its line and column, and recovery that keeps reading after an error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/scenes/scene_parser.hpp"

namespace {

using namespace sandpaper;
using compiler::Diagnostics;
using scenes::ShapeKind;
using scenes::Side;

const std::filesystem::path kSource = SANDPAPER_SOURCE_DIR;

// The example of schema/LANGUAGE.md, "Scenes", and the scene_file fuzz target's first seed.
constexpr const char* kExample = R"(# A textured ball above a floor.
scene "ball and floor" {
  object "ball" sphere radius 50 mm at 0 mm, 60 mm, 0 mm {
    material "corduroy"
    stiffness 800 N/m
    friction 0.5 0.3
  }
  object "floor" plane 300 mm x 300 mm at 0 mm, 0 mm, 0 mm {
    material "sandpaper-p80"
  }
  object "crate" box 80 mm x 40 mm x 80 mm at 100 mm, 20 mm, 0 mm {
    material "silk-satin"
    material "gravel" on top
  }
}
)";

struct Parsed {
  scenes::SceneSyntax scene;
  Diagnostics diags;
};

Parsed parse(const std::string& text) {
  auto file = std::make_shared<const compiler::SourceFile>("t.hsc", text);
  Parsed p;
  const auto tokens = compiler::lex(file, p.diags, compiler::LexOptions{.commas = true});
  p.scene = scenes::parse_scene(tokens, file, p.diags);
  return p;
}

// "E0810 3:22" for each diagnostic, in order.
std::vector<std::string> found(const Diagnostics& d) {
  std::vector<std::string> out;
  for (const auto& x : d.all())
    out.push_back(x.code + " " + std::to_string(x.location.line) + ":" + std::to_string(x.location.column));
  return out;
}

// `text` inside a scene block on line 2: "scene \"s\" {\n" + text + "\n}\n".
std::string in_scene(const std::string& text) { return "scene \"s\" {\n" + text + "\n}\n"; }

// One object on line 2 whose block holds `stmts` from line 3 on.
std::string in_object(const std::string& shape, const std::string& stmts) {
  return in_scene("object \"o\" " + shape + " at 0 mm, 0 mm, 0 mm {\n" + stmts + "\n}");
}
const std::string kBox = "box 10 mm x 20 mm x 30 mm";

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The column (from 1) of the first `what` on line `line` (from 1) of `text`.
int column_of(const std::string& text, int line, const std::string& what) {
  std::size_t start = 0;
  for (int i = 1; i < line; ++i) start = text.find('\n', start) + 1;
  return static_cast<int>(text.find(what, start) - start) + 1;
}

TEST(SceneParser, TheExampleReadsInSIUnits) {
  const auto p = parse(kExample);
  ASSERT_TRUE(p.diags.all().empty()) << compiler::format_diagnostics(p.diags);
  EXPECT_EQ(p.scene.name, "ball and floor");
  ASSERT_EQ(p.scene.objects.size(), 3u);

  const auto& ball = p.scene.objects[0];
  EXPECT_EQ(ball.name, "ball");
  EXPECT_EQ(ball.shape, ShapeKind::Sphere);
  ASSERT_TRUE(ball.radius);
  EXPECT_DOUBLE_EQ(ball.radius->si, 0.05);
  EXPECT_DOUBLE_EQ(ball.x.si, 0.0);
  EXPECT_DOUBLE_EQ(ball.y.si, 0.06);
  EXPECT_DOUBLE_EQ(ball.z.si, 0.0);
  ASSERT_EQ(ball.surfaces.size(), 1u);
  EXPECT_EQ(ball.surfaces[0].material, "corduroy");
  EXPECT_FALSE(ball.surfaces[0].side);
  ASSERT_TRUE(ball.stiffness);
  EXPECT_DOUBLE_EQ(ball.stiffness->si, 800.0);
  EXPECT_EQ(ball.stiffness->unit, "N/m");
  EXPECT_EQ(ball.static_friction, 0.5);
  EXPECT_EQ(ball.kinetic_friction, 0.3);
  EXPECT_FALSE(ball.damping);
  EXPECT_FALSE(ball.texture_width);

  const auto& floor = p.scene.objects[1];
  EXPECT_EQ(floor.shape, ShapeKind::Plane);
  ASSERT_TRUE(floor.size[0] && floor.size[2]);
  EXPECT_FALSE(floor.size[1]);
  EXPECT_DOUBLE_EQ(floor.size[0]->si, 0.3);
  EXPECT_DOUBLE_EQ(floor.size[2]->si, 0.3);
  EXPECT_EQ(floor.facing, Side::Top);
  EXPECT_FALSE(floor.static_friction);
  ASSERT_EQ(floor.surfaces.size(), 1u);
  EXPECT_EQ(floor.surfaces[0].material, "sandpaper-p80");

  const auto& crate = p.scene.objects[2];
  EXPECT_EQ(crate.shape, ShapeKind::Box);
  EXPECT_FALSE(crate.inside);
  EXPECT_DOUBLE_EQ(crate.size[0]->si, 0.08);
  EXPECT_DOUBLE_EQ(crate.size[1]->si, 0.04);
  EXPECT_DOUBLE_EQ(crate.size[2]->si, 0.08);
  EXPECT_DOUBLE_EQ(crate.x.si, 0.1);
  EXPECT_DOUBLE_EQ(crate.y.si, 0.02);
  ASSERT_EQ(crate.surfaces.size(), 2u);
  EXPECT_EQ(crate.surfaces[0].material, "silk-satin");
  EXPECT_FALSE(crate.surfaces[0].side);
  EXPECT_EQ(crate.surfaces[1].material, "gravel");
  EXPECT_EQ(crate.surfaces[1].side, Side::Top);
}

TEST(SceneParser, LocationsPointAtTheirWords) {
  const std::string text = kExample;
  const auto p = parse(text);
  ASSERT_EQ(p.scene.objects.size(), 3u);
  EXPECT_EQ(p.scene.name_location.line, 2);
  EXPECT_EQ(p.scene.name_location.column, 7);
  const auto& ball = p.scene.objects[0];
  EXPECT_EQ(ball.location.line, 3);
  EXPECT_EQ(ball.location.column, 3);
  EXPECT_EQ(ball.name_location.column, column_of(text, 3, "\"ball\""));
  EXPECT_EQ(ball.shape_location.column, column_of(text, 3, "sphere"));
  // `at` spans X, Y, Z: "0 mm, 60 mm, 0 mm".
  EXPECT_EQ(ball.at_location.line, 3);
  EXPECT_EQ(ball.at_location.column, column_of(text, 3, "0 mm, 60"));
  EXPECT_EQ(ball.at_location.length, static_cast<int>(std::string("0 mm, 60 mm, 0 mm").size()));
  EXPECT_EQ(ball.radius->location.column, column_of(text, 3, "50 mm"));
  EXPECT_EQ(ball.radius->location.length, 5);
  EXPECT_EQ(ball.stiffness->location.line, 5);
  EXPECT_EQ(ball.friction_location.line, 6);
  EXPECT_EQ(ball.friction_location.column, 5);
  const auto& gravel = p.scene.objects[2].surfaces[1];
  EXPECT_EQ(gravel.location.line, 13);
  EXPECT_EQ(gravel.location.column, 5);
  EXPECT_EQ(gravel.material_location.column, column_of(text, 13, "\"gravel\""));
}

TEST(SceneParser, TheExampleIsTheFirstFuzzSeedAndTheLanguagesExample) {
  EXPECT_EQ(read(kSource / "fuzz/corpus/scene_file/ball-and-floor.hsc"), kExample);
  const std::string language = read(kSource / "schema/LANGUAGE.md");
  EXPECT_NE(language.find(std::string("```\n") + kExample + "```\n"), std::string::npos)
      << "schema/LANGUAGE.md, \"Scenes\", shows another example than the one tested here";
}

TEST(SceneParser, EveryOtherFormOfTheGrammar) {
  const auto p = parse(R"(scene "forms" {
  object "room" box 2 m x 2.5 m x 3 m inside at 0 m, 1.25 m, 0 m {
    material "window-glass"; material "velvet" on bottom
    material "corduroy" on front
    damping 2 N*s/m
    stiffness 0.8 N/mm
    friction 0.4
    texture size 40 mm x 20 mm
  }
  object "wall" plane 1 in x 2 in facing front at -10 cm, 0 mm, -5 mm
  object "one line" sphere radius 1 cm at 1e1 mm, 0 mm, 0 mm { material "a10p25"; texture size 5 mm }
  object "bare" sphere radius 1 cm at 0 mm, 0 mm, 0 mm {
  }
}
)");
  ASSERT_TRUE(p.diags.all().empty()) << compiler::format_diagnostics(p.diags);
  ASSERT_EQ(p.scene.objects.size(), 4u);
  const auto& room = p.scene.objects[0];
  EXPECT_TRUE(room.inside);
  EXPECT_DOUBLE_EQ(room.size[1]->si, 2.5);
  ASSERT_EQ(room.surfaces.size(), 3u);
  EXPECT_EQ(room.surfaces[1].side, Side::Bottom);
  EXPECT_EQ(room.surfaces[2].side, Side::Front);
  EXPECT_DOUBLE_EQ(room.damping->si, 2.0);
  EXPECT_DOUBLE_EQ(room.stiffness->si, 800.0);  // 0.8 N/mm
  EXPECT_EQ(room.static_friction, 0.4);
  EXPECT_EQ(room.kinetic_friction, 0.4);  // one number: both
  EXPECT_DOUBLE_EQ(room.texture_width->si, 0.04);
  EXPECT_DOUBLE_EQ(room.texture_height->si, 0.02);
  EXPECT_EQ(room.texture_location.line, 8);

  const auto& wall = p.scene.objects[1];
  EXPECT_EQ(wall.shape, ShapeKind::Plane);
  EXPECT_EQ(wall.facing, Side::Front);
  EXPECT_EQ(wall.facing_location.line, 10);
  EXPECT_DOUBLE_EQ(wall.size[0]->si, 0.0254);
  EXPECT_DOUBLE_EQ(wall.size[2]->si, 0.0508);
  EXPECT_DOUBLE_EQ(wall.x.si, -0.1);
  EXPECT_DOUBLE_EQ(wall.z.si, -0.005);
  EXPECT_TRUE(wall.surfaces.empty());

  const auto& one = p.scene.objects[2];
  EXPECT_DOUBLE_EQ(one.x.si, 0.01);
  ASSERT_EQ(one.surfaces.size(), 1u);
  EXPECT_DOUBLE_EQ(one.texture_width->si, 0.005);
  EXPECT_FALSE(one.texture_height);  // H absent: the compiler takes W
  EXPECT_TRUE(p.scene.objects[3].surfaces.empty());
}

TEST(SceneParser, AnEmptySceneAndBlankLinesAreFine) {
  for (const char* text : {"scene \"empty\" {}", "\n\n# only a comment\nscene \"empty\" {\n\n}\n\n", "scene \"\" {\n}"}) {
    const auto p = parse(text);
    EXPECT_TRUE(p.diags.all().empty()) << text << "\n" << compiler::format_diagnostics(p.diags);
    EXPECT_TRUE(p.scene.objects.empty());
  }
}

struct ErrorCase {
  std::string text;
  std::vector<std::string> expected;  // "CODE line:col", in order
  std::string in_message_or_help;     // a phrase the first diagnostic's message or suggestion holds
};

TEST(SceneParser, EachErrorAtItsPlace) {
  const std::string sphere = "object \"o\" sphere radius 5 mm at 0 mm, 0 mm, 0 mm";
  const std::vector<ErrorCase> cases = {
      // E0801: no `scene`, no '{', not a word where a statement starts, `texture` without `size`
      {"object \"o\" sphere radius 5 mm at 0 mm, 0 mm, 0 mm", {"E0801 1:1"}, "expected `scene`"},
      {"scene \"s\"\n" + sphere + "\n}", {"E0801 1:10"}, "expected '{'"},
      {in_scene("42"), {"E0801 2:1"}, "expected an object"},
      {in_object(kBox, "\"x\""), {"E0801 3:1"}, "expected an object statement"},
      {in_object(kBox, "texture 5 mm"), {"E0801 3:9"}, "expected `size` or `relief` after `texture`"},
      {in_object(kBox, "texture depth 5 mm"), {"E0801 3:9"}, "texture relief 0.5 mm (only)"},
      // E0802: unknown statements, with "did you mean"; an object statement outside an object
      {in_scene("objekt \"o\" sphere radius 5 mm at 0 mm, 0 mm, 0 mm"), {"E0802 2:1"}, "did you mean `object`?"},
      {in_scene("stiffness 800 N/m"), {"E0802 2:1"}, "belongs in an object's block"},
      {in_object(kBox, "stifness 800 N/m"), {"E0802 3:1"}, "did you mean `stiffness`?"},
      {in_object(kBox, "roughness 0.5"), {"E0802 3:1"}, "an object holds"},
      // E0803: blocks not closed
      {"scene \"s\" {\n" + sphere, {"E0803 1:7"}, "the scene block is not closed"},
      {"scene \"s\" {\n" + sphere + " {\n  material \"a\"\n", {"E0803 2:51", "E0803 1:7"}, "object \"o\" is not closed"},
      // E0804
      {"scene \"s\" {\n}\nscene \"t\" {\n}", {"E0804 3:1"}, "text after the scene block"},
      {"scene \"s\" {\n} }", {"E0804 2:3"}, "text after the scene block"},
      // E0805: a statement twice in one object, the note at the first
      {in_object(kBox, "stiffness 800 N/m\nstiffness 900 N/m"), {"E0805 4:1"}, "stiffness is given twice"},
      {in_object(kBox, "damping 1 N*s/m\ndamping 1 N*s/m"), {"E0805 4:1"}, "damping is given twice"},
      {in_object(kBox, "friction 0.5\nfriction 0.5"), {"E0805 4:1"}, "friction is given twice"},
      {in_object(kBox, "texture size 5 mm\ntexture size 5 mm"), {"E0805 4:1"}, "texture size is given twice"},
      {in_object(kBox, "texture relief 0.5 mm\ntexture relief 0.3 mm only"), {"E0805 4:1"}, "texture relief is given twice"},
      {in_object(kBox, "material \"a\"\nmaterial \"b\""), {"E0805 4:1"}, "for all its surfaces twice"},
      {in_object(kBox, "material \"a\" on top\nmaterial \"b\" on bottom\nmaterial \"c\" on top"), {"E0805 5:1"},
       "top side is given a material twice"},
      // E0806: sizes that are not positive
      {in_scene("object \"o\" sphere radius -5 mm at 0 mm, 0 mm, 0 mm"), {"E0806 2:26"}, "the sphere's radius must be positive, not -5 mm"},
      {in_scene("object \"o\" box 10 mm x 0 mm x 10 mm at 0 mm, 0 mm, 0 mm"), {"E0806 2:24"}, "height (y) must be positive"},
      {in_scene("object \"o\" plane 10 mm x -1 mm at 0 mm, 0 mm, 0 mm"), {"E0806 2:26"}, "the plane's depth must be positive"},
      {in_object(kBox, "texture size 0 mm"), {"E0806 3:14"}, "the texture's width must be positive"},
      {in_object(kBox, "texture relief 0 mm"), {"E0806 3:16"}, "the relief's depth must be positive, not 0 mm"},
      {in_object(kBox, "texture relief -0.5 mm only"), {"E0806 3:16"}, "the relief's depth must be positive"},
      // E0814: a relief deeper than 10 mm
      {in_object(kBox, "texture relief 11 mm"), {"E0814 3:16"}, "a relief of 11 mm is deeper than 10 mm"},
      {in_object(kBox, "texture relief 1 cm only"), {}, ""},
      {in_object(kBox, "texture relief 1.01 cm"), {"E0814 3:16"}, "deeper than 10 mm"},
      // E0807: unknown or incomplete shapes
      {in_scene("object \"o\" sphear radius 5 mm at 0 mm, 0 mm, 0 mm"), {"E0807 2:12"}, "did you mean `sphere`?"},
      {in_scene("object \"o\" cylinder at 0 mm, 0 mm, 0 mm"), {"E0807 2:12"}, "the shapes are sphere, box and plane"},
      {in_scene("object \"o\" at 0 mm, 0 mm, 0 mm"), {"E0807 2:12"}, "unknown shape 'at'"},
      {in_scene("object \"o\" sphere 5 mm at 0 mm, 0 mm, 0 mm"), {"E0807 2:19"}, "expected `radius` after `sphere`"},
      {in_scene("object \"o\" box 80 mm x 40 mm at 0 mm, 0 mm, 0 mm"), {"E0807 2:30"}, "a box has three sizes"},
      {in_scene("object \"o\" plane 80 mm at 0 mm, 0 mm, 0 mm"), {"E0807 2:24"}, "a plane has two sizes"},
      // E0808: empty name, empty material
      {in_scene("object \" \" sphere radius 5 mm at 0 mm, 0 mm, 0 mm"), {"E0808 2:8"}, "empty name"},
      {in_object(kBox, "material \"\""), {"E0808 3:10"}, "empty material"},
      // E0810: sides
      {in_object(kBox, "material \"a\" on botom"), {"E0810 3:17"}, "did you mean `bottom`?"},
      {in_object(kBox, "material \"a\" on 3"), {"E0810 3:17"}, "expected a side after `on`"},
      {in_scene("object \"o\" plane 1 m x 1 m facing up at 0 mm, 0 mm, 0 mm"), {"E0810 2:35"}, "unknown side 'up'"},
      // E0811: an option of another shape
      {in_object("sphere radius 5 mm", "material \"a\" on top"), {"E0811 3:14"}, "only a box has sides"},
      {in_object("plane 1 m x 1 m", "material \"a\" on top"), {"E0811 3:14"}, "facing SIDE"},
      {in_scene("object \"o\" sphere radius 5 mm inside at 0 mm, 0 mm, 0 mm"), {"E0811 2:31"}, "only a box can be felt from inside"},
      {in_scene("object \"o\" plane 1 m x 1 m inside at 0 mm, 0 mm, 0 mm"), {"E0811 2:28"}, "only a box can be felt from inside"},
      {in_scene("object \"o\" box 1 m x 1 m x 1 m facing top at 0 mm, 0 mm, 0 mm"), {"E0811 2:32"}, "only a plane has a facing"},
      // E0812: contact values out of range
      {in_object(kBox, "stiffness 0 N/m"), {"E0812 3:11"}, "the stiffness must be positive"},
      {in_object(kBox, "stiffness -800 N/m"), {"E0812 3:11"}, "the stiffness must be positive"},
      {in_object(kBox, "damping -1 N*s/m"), {"E0812 3:9"}, "the damping must not be negative"},
      {in_object(kBox, "friction -0.1"), {"E0812 3:10"}, "must not be negative"},
      {in_object(kBox, "friction 0.5 -0.1"), {"E0812 3:14"}, "must not be negative"},
      {in_object(kBox, "friction 0.3 0.5"), {"E0812 3:14"}, "friction 0.5 0.3 (static first)"},
      // E0813: two objects, one name; the note points at the first
      {in_scene(sphere + "\n" + sphere), {"E0813 3:8"}, "two objects are named \"o\""},
      // E0831: quoted texts
      {"scene ball {\n}", {"E0831 1:7"}, "the scene's name"},  // the unquoted name stepped over, '{' read
      {in_scene("object ball sphere radius 5 mm at 0 mm, 0 mm, 0 mm"), {"E0831 2:8"}, "the object's name"},
      {in_object(kBox, "material corduroy"), {"E0831 3:10"}, "the material as a quoted string"},
      // E0832: `at X, Y, Z`
      {in_scene("object \"o\" sphere radius 5 mm 0 mm, 0 mm, 0 mm"), {"E0832 2:31"}, "expected `at`"},
      {in_scene("object \"o\" sphere radius 5 mm at 0 mm 0 mm, 0 mm"), {"E0832 2:39"}, "between the centre's x and y"},
      {in_scene("object \"o\" sphere radius 5 mm at 0 mm, 0 mm"), {"E0832 2:44"}, "between the centre's y and z"},
      // E0833: numbers
      {in_object(kBox, "stiffness N/m"), {"E0833 3:11"}, "expected the stiffness"},
      {in_object(kBox, "friction"), {"E0833 3:9"}, "expected the static friction"},
      {in_scene("object \"o\" sphere radius five at 0 mm, 0 mm, 0 mm"), {"E0833 2:26"}, "the sphere's radius"},
      // E0834: more after a complete statement
      {in_scene(sphere + " extra"), {"E0834 2:51"}, "after the statement"},
      {in_scene(sphere + " inside"), {"E0834 2:51"}, "write `inside` after the shape's sizes, before `at`"},
      {in_object(kBox, "friction 0.5 0.3 0.1"), {"E0834 3:18"}, "after the statement"},
      {in_object(kBox, "texture relief 0.5 mm all"), {"E0834 3:23"}, "after the statement"},
      {in_object(kBox, "material \"a\" on top bottom"), {"E0834 3:21"}, "after the statement"},
      {in_scene(sphere + " {\n} x"), {"E0834 3:3"}, "after the statement"},
      // The material language's unit errors and bounds
      {in_scene("object \"o\" sphere radius 5 at 0 mm, 0 mm, 0 mm"), {"E0203 2:26"}, "`5` has no unit"},
      {in_scene("object \"o\" sphere radius 5 mn at 0 mm, 0 mm, 0 mm"), {"E0204 2:28"}, "unknown unit 'mn'"},
      {in_scene("object \"o\" sphere radius 5 N at 0 mm, 0 mm, 0 mm"), {"E0205 2:28"}, "is a force unit"},
      {in_object(kBox, "stiffness 800 N*s/m"), {"E0205 3:15"}, "is a damping unit"},
      {in_object(kBox, "friction 0.5 N"), {"E0205 3:14"}, "takes no unit"},
      {in_object(kBox, "texture relief 0.5"), {"E0203 3:16"}, "the relief's depth is a length"},
      {in_object(kBox, "texture relief 0.5 N"), {"E0205 3:20"}, "is a force unit"},
      {in_object(kBox, "texture relief only"), {"E0833 3:16"}, "expected the relief's depth"},
      {in_scene("object \"o\" sphere radius 1e300 m at 0 mm, 0 mm, 0 mm"), {"E0103 2:26"}, "between 1e-12 and 1e12 m"},
      {in_scene("object \"o\" sphere radius 1 m at 1e-20 m, 0 mm, 0 mm"), {"E0103 2:33"}, "the centre's x"},
      {in_object(kBox, "friction 1e20"), {"E0103 3:10"}, "the static friction"},
  };
  for (const auto& c : cases) {
    const auto p = parse(c.text);
    EXPECT_EQ(found(p.diags), c.expected) << c.text << "\n" << compiler::format_diagnostics(p.diags);
    if (p.diags.all().empty()) continue;
    const auto& d = p.diags.all()[0];
    EXPECT_NE((d.message + " | " + d.suggestion).find(c.in_message_or_help), std::string::npos)
        << c.text << "\n" << d.message << " | " << d.suggestion;
  }
}

// `texture relief D [only]`: the depth in SI units, `only` read, beside `texture size`; without
// `only` the lateral texture is kept.
TEST(SceneParser, TextureReliefReadsItsDepthAndOnly) {
  const auto p = parse(in_scene("object \"a\" plane 1 m x 1 m at 0 mm, 0 mm, 0 mm {\n"
                                "  texture size 40 mm\n  texture relief 0.5 mm only\n}\n"
                                "object \"b\" sphere radius 5 cm at 0 mm, 0 mm, 0 mm {\n  texture relief 200 um; material \"m\"\n}\n"
                                "object \"c\" sphere radius 5 cm at 0 mm, 0 mm, 0 mm"));
  ASSERT_TRUE(p.diags.all().empty()) << compiler::format_diagnostics(p.diags);
  ASSERT_EQ(p.scene.objects.size(), 3u);
  const auto& a = p.scene.objects[0];
  ASSERT_TRUE(a.relief_depth);
  EXPECT_DOUBLE_EQ(a.relief_depth->si, 0.0005);
  EXPECT_TRUE(a.relief_only);
  EXPECT_EQ(a.relief_location.line, 4);
  EXPECT_EQ(a.relief_location.column, 3);
  ASSERT_TRUE(a.texture_width);
  EXPECT_DOUBLE_EQ(a.texture_width->si, 0.04);
  const auto& b = p.scene.objects[1];
  ASSERT_TRUE(b.relief_depth);
  EXPECT_DOUBLE_EQ(b.relief_depth->si, 0.0002);
  EXPECT_FALSE(b.relief_only);
  EXPECT_EQ(b.surfaces.size(), 1u);
  EXPECT_FALSE(p.scene.objects[2].relief_depth);
  // A relief with an error leaves none behind.
  const auto bad = parse(in_object(kBox, "texture relief 20 mm only"));
  ASSERT_EQ(bad.scene.objects.size(), 1u);
  EXPECT_FALSE(bad.scene.objects[0].relief_depth);
  EXPECT_FALSE(bad.scene.objects[0].relief_only);
}

TEST(SceneParser, RepeatsNameTheFirstInANote) {
  const auto p = parse(in_object(kBox, "material \"a\" on top\nstiffness 800 N/m\nmaterial \"b\" on top\nstiffness 1 N/mm"));
  ASSERT_EQ(found(p.diags), (std::vector<std::string>{"E0805 5:1", "E0805 6:1"}));
  ASSERT_EQ(p.diags.all()[0].notes.size(), 1u);
  EXPECT_EQ(p.diags.all()[0].notes[0].location.line, 3);
  ASSERT_EQ(p.diags.all()[1].notes.size(), 1u);
  EXPECT_EQ(p.diags.all()[1].notes[0].location.line, 4);
  // The first of each is kept.
  ASSERT_EQ(p.scene.objects.size(), 1u);
  ASSERT_EQ(p.scene.objects[0].surfaces.size(), 1u);
  EXPECT_EQ(p.scene.objects[0].surfaces[0].material, "a");
  EXPECT_DOUBLE_EQ(p.scene.objects[0].stiffness->si, 800.0);

  const auto twice = parse(in_scene("object \"o\" sphere radius 5 mm at 0 mm, 0 mm, 0 mm\n"
                                    "object \"o\" sphere radius 5 mm at 1 mm, 0 mm, 0 mm"));
  ASSERT_EQ(twice.diags.all().size(), 1u);
  ASSERT_EQ(twice.diags.all()[0].notes.size(), 1u);
  EXPECT_EQ(twice.diags.all()[0].notes[0].location.line, 2);
  EXPECT_EQ(twice.diags.all()[0].notes[0].location.column, 8);
}

TEST(SceneParser, AStatementWithAnErrorLeavesNothingInItsObject) {
  const auto p = parse(in_object(kBox, "stiffness 0 N/m\ndamping -1 N*s/m\nfriction 0.3 0.5\ntexture size 5 mm x 0 mm\n"
                                       "material \"\"\nmaterial \"a\" on up"));
  EXPECT_EQ(p.diags.all().size(), 6u) << compiler::format_diagnostics(p.diags);
  ASSERT_EQ(p.scene.objects.size(), 1u);
  const auto& o = p.scene.objects[0];
  EXPECT_FALSE(o.stiffness);
  EXPECT_FALSE(o.damping);
  EXPECT_FALSE(o.static_friction);
  EXPECT_FALSE(o.kinetic_friction);
  EXPECT_FALSE(o.texture_width);
  EXPECT_TRUE(o.surfaces.empty());
}

TEST(SceneParser, RecoveryReportsEveryErrorAndKeepsTheGoodObjects) {
  const std::string text = R"(scene "s" {
  object "a" sphear radius 5 mm at 0 mm, 0 mm, 0 mm {
    material "x" on top
    stifness 800 N/m
  }
  object "b" sphere radius 5 mm at 0 mm, 0 mm, 0 mm {
    friction 0.3 0.5
    material "corduroy"
    damping 2 N*s/m extra
    stiffness 800 N/m
  }
  object "c" box 1 m x 1 m x 1 m at 0 mm, 0 mm, 0 mm { material "a" on up; friction 0.5 }
  object "d" sphere radius -1 mm at 0 mm, 0 mm, 0 mm {
    material "a" on top
    frction 0.5
  }
}
)";
  const auto p = parse(text);
  // Object a's first line is wrong, but its block is read (its statements' errors reported, its '}'
  // closing it and not the scene; `on top` is not checked against a shape it does not have); b
  // keeps what was right; c recovers at ';' inside its block; d's block is read knowing it is a
  // sphere.
  EXPECT_EQ(found(p.diags), (std::vector<std::string>{
                                "E0807 2:14", "E0802 4:5", "E0812 7:18", "E0834 9:21",
                                "E0810 12:" + std::to_string(column_of(text, 12, "up;")), "E0806 13:28", "E0811 14:18",
                                "E0802 15:5"}));
  ASSERT_EQ(p.scene.objects.size(), 2u);
  const auto& b = p.scene.objects[0];
  EXPECT_EQ(b.name, "b");
  ASSERT_EQ(b.surfaces.size(), 1u);
  EXPECT_EQ(b.surfaces[0].material, "corduroy");
  EXPECT_FALSE(b.static_friction);
  EXPECT_TRUE(b.damping);  // the statement was whole: the text after it is the error
  EXPECT_DOUBLE_EQ(b.stiffness->si, 800.0);
  const auto& c = p.scene.objects[1];
  EXPECT_EQ(c.name, "c");
  EXPECT_TRUE(c.surfaces.empty());
  EXPECT_EQ(c.static_friction, 0.5);
}

TEST(SceneParser, AnObjectWhoseBlockIsNotClosedEndsAtTheNextObject) {
  const auto p = parse(R"(scene "s" {
  object "a" sphere radius 5 mm at 0 mm, 0 mm, 0 mm {
    material "corduroy"
  object "b" sphere radius 5 mm at 0 mm, 0 mm, 0 mm {
    material "velvet"
  }
}
)");
  EXPECT_EQ(found(p.diags), (std::vector<std::string>{"E0803 2:53"}));
  ASSERT_EQ(p.scene.objects.size(), 2u);
  EXPECT_EQ(p.scene.objects[0].surfaces.at(0).material, "corduroy");
  EXPECT_EQ(p.scene.objects[1].surfaces.at(0).material, "velvet");
}

TEST(SceneParser, ABlockInsideAStatementIsSteppedOverWhole) {
  // A '{' after a statement opens a block that is skipped to its own '}', so the object's '}' still
  // closes the object; nesting is counted, not recursed into.
  const std::string deep(100000, '{');
  const std::string closing(100000, '}');
  const auto p = parse(in_object(kBox, "material \"a\" {\n  stiffness 800 N/m\n}\nfriction 0.5\n" + deep + "\n" +
                                           closing + "\ndamping 1 N*s/m"));
  EXPECT_EQ(found(p.diags), (std::vector<std::string>{"E0834 3:14", "E0801 7:1"}));
  ASSERT_EQ(p.scene.objects.size(), 1u);
  EXPECT_FALSE(p.scene.objects[0].stiffness);
  EXPECT_EQ(p.scene.objects[0].static_friction, 0.5);
  EXPECT_TRUE(p.scene.objects[0].damping);
}

TEST(SceneParser, TheEndOfTheFileAnywhereIsAnErrorNotACrash) {
  const std::string text = kExample;
  // Every prefix of the example: whatever it reads, each diagnostic lies within the text.
  for (std::size_t n = 0; n < text.size(); ++n) {
    const auto p = parse(text.substr(0, n));
    const bool whole = n >= text.rfind('}') + 1;
    EXPECT_EQ(p.diags.has_errors(), !whole) << n;
    for (const auto& d : p.diags.all()) {
      EXPECT_GE(d.location.line, 1) << n;
      EXPECT_LE(d.location.line, 17) << n;
    }
  }
}

TEST(SceneParser, MoreObjectsThanTheLimitAreRefusedOnce) {
  std::string text = "scene \"many\" {\n";
  for (std::size_t i = 0; i < scenes::kMaxSceneObjects + 3; ++i)
    text += "object \"o" + std::to_string(i) + "\" sphere radius 1 mm at 0 mm, 0 mm, 0 mm\n";
  text += "}\n";
  const auto p = parse(text);
  const int first_past = static_cast<int>(scenes::kMaxSceneObjects) + 2;  // line of object kMax + 1
  EXPECT_EQ(found(p.diags), (std::vector<std::string>{"E0809 " + std::to_string(first_past) + ":1"}));
  EXPECT_EQ(p.scene.objects.size(), scenes::kMaxSceneObjects);
}

TEST(SceneParser, DiagnosticsPrintWithTheirCaretAndSuggestion) {
  const auto p = parse(in_object(kBox, "material \"a\" on botom"));
  ASSERT_EQ(p.diags.all().size(), 1u);
  const std::string printed = compiler::format_diagnostic(p.diags.all()[0]);
  EXPECT_NE(printed.find("t.hsc:3:17: error[E0810]: unknown side 'botom'\n 3 | material \"a\" on botom\n"
                         "   |                 ^~~~~\n"),
            std::string::npos)
      << printed;
  EXPECT_NE(printed.find("did you mean `bottom`?"), std::string::npos) << printed;
}

TEST(SceneParser, TokensWithoutEofAreABug) {
  auto file = std::make_shared<const compiler::SourceFile>("t.hsc", "");
  Diagnostics d;
  EXPECT_THROW(scenes::parse_scene({}, file, d), compiler::InternalError);
}

TEST(SceneParser, ScenePathsAndSideNames) {
  EXPECT_TRUE(scenes::is_scene_path("examples/scenes/ball.hsc"));
  EXPECT_TRUE(scenes::is_scene_path("a.b.hsc"));
  EXPECT_FALSE(scenes::is_scene_path("ball.hws"));
  EXPECT_FALSE(scenes::is_scene_path("ball.hsc.bak"));
  EXPECT_FALSE(scenes::is_scene_path("hsc"));
  EXPECT_STREQ(scenes::side_name(Side::Top), "top");
  EXPECT_STREQ(scenes::side_name(Side::Bottom), "bottom");
  EXPECT_STREQ(scenes::side_name(Side::Right), "right");
  EXPECT_STREQ(scenes::side_name(Side::Left), "left");
  EXPECT_STREQ(scenes::side_name(Side::Front), "front");
  EXPECT_STREQ(scenes::side_name(Side::Back), "back");
  // Every side name reads back as its side.
  for (const Side s : {Side::Top, Side::Bottom, Side::Right, Side::Left, Side::Front, Side::Back}) {
    const auto p = parse(in_object(kBox, std::string("material \"a\" on ") + scenes::side_name(s)));
    ASSERT_EQ(p.scene.objects.size(), 1u) << compiler::format_diagnostics(p.diags);
    EXPECT_EQ(p.scene.objects[0].surfaces.at(0).side, s);
  }
}

}  // namespace
