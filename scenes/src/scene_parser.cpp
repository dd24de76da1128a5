#include "sandpaper/scenes/scene_parser.hpp"

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <map>
#include <string_view>

#include "sandpaper/schema/units.hpp"
#include "sandpaper/shapes/scene_io.hpp"

namespace sandpaper::scenes {
namespace {

using compiler::closest_match;
using compiler::Diagnostics;
using compiler::SourceFile;
using compiler::Token;
using compiler::TokenKind;
using schema::Dimension;

// The material language's bounds on a quantity in SI units (E0103): outside them no number describes
// something a hand can feel, and the extremes overflow the renderer's arithmetic.
constexpr double kLeastQuantitySI = 1e-12;
constexpr double kGreatestQuantitySI = 1e12;

constexpr Side kSides[] = {Side::Top, Side::Bottom, Side::Right, Side::Left, Side::Front, Side::Back};

const std::vector<std::string>& side_words() {
  static const std::vector<std::string> k{"top", "bottom", "right", "left", "front", "back"};
  return k;
}
const std::vector<std::string>& shape_words() {
  static const std::vector<std::string> k{"sphere", "box", "plane"};
  return k;
}
const std::vector<std::string>& object_keywords() {
  static const std::vector<std::string> k{"material", "stiffness", "damping", "friction", "texture"};
  return k;
}

const char* shape_word(ShapeKind k) {
  switch (k) {
    case ShapeKind::Sphere: return "sphere";
    case ShapeKind::Box: return "box";
    case ShapeKind::Plane: return "plane";
  }
  return "?";
}

std::string example(Dimension d) {
  switch (d) {
    case Dimension::Stiffness: return "800 N/m";
    case Dimension::Damping: return "2 N*s/m";
    default: return "50 mm";
  }
}

// Thrown inside a statement to abandon it; the diagnostic has already been recorded.
struct StatementError {};

// The compiler's token cursor (compiler/src/front/token_cursor.hpp) is internal to its library; this
// is the same few steps: the token at hand, stepping past it (never past Eof), skipping line ends,
// and a token as a message names it.
class TokenCursor {
 protected:
  explicit TokenCursor(const std::vector<Token>& tokens) : toks_(tokens) {}

  const Token& peek() const { return toks_[pos_]; }
  const Token& next() {
    const Token& t = toks_[pos_];
    if (pos_ + 1 < toks_.size()) ++pos_;
    return t;
  }
  void skip_ends() {
    while (peek().kind == TokenKind::End) next();
  }
  bool at_word(std::string_view w) const { return peek().kind == TokenKind::Word && peek().text == w; }
  static std::string describe(const Token& t) {
    switch (t.kind) {
      case TokenKind::Word: return "'" + t.text + "'";
      case TokenKind::Number: return "the number " + t.text;
      case TokenKind::String: return "the string \"" + t.text + "\"";
      default: return compiler::token_kind_name(t.kind);
    }
  }

 private:
  const std::vector<Token>& toks_;
  std::size_t pos_ = 0;
};

class SceneParser : TokenCursor {
 public:
  SceneParser(const std::vector<Token>& tokens, std::shared_ptr<const SourceFile> file, Diagnostics& diags)
      : TokenCursor(tokens), file_(std::move(file)), diags_(diags) {}

  // scene_file := End* 'scene' STRING '{' (object? End)* '}' End* Eof
  SceneSyntax file() {
    SceneSyntax scene;
    scene.file = file_;
    skip_ends();
    if (!at_word("scene")) {
      diags_.error("E0801", peek().location, "expected `scene`, found " + describe(peek()),
                   "a scene file is one block: scene \"name\" { object \"ball\" sphere radius 50 mm at 0 mm, 60 mm, 0 mm }");
      return scene;
    }
    next();
    if (peek().kind != TokenKind::String) {
      diags_.error("E0831", peek().location, "expected the scene's name as a string, found " + describe(peek()),
                   "write scene \"name\" { ... }");
      // A name without its quotes: step over it, so that the '{' after it is read as one.
      if (peek().kind == TokenKind::Word || peek().kind == TokenKind::Number) next();
    } else {
      scene.name = peek().text;
      scene.name_location = next().location;
    }
    const SourceLocation block_start = scene.name_location.file ? scene.name_location : peek().location;
    if (peek().kind != TokenKind::LBrace) {
      diags_.error("E0801", peek().location, "expected '{' after the scene name, found " + describe(peek()),
                   "open the scene's body with '{'");
      // Read the objects anyway so that their errors are reported too.
    } else {
      next();
    }
    objects(scene);
    if (peek().kind == TokenKind::RBrace) {
      next();
    } else {
      diags_.error("E0803", block_start, "the scene block is not closed", "add '}' after its last object");
      return scene;
    }
    skip_ends();
    if (peek().kind != TokenKind::Eof)
      diags_.error("E0804", peek().location, "text after the scene block",
                   "a file holds one scene; move this into the block or into a file of its own");
    return scene;
  }

 private:
  // (object? End)*   -- stops at '}' or the end of the file
  void objects(SceneSyntax& scene) {
    while (true) {
      skip_ends();
      if (peek().kind == TokenKind::Eof || peek().kind == TokenKind::RBrace) return;
      try {
        scene_statement(scene);
      } catch (const StatementError&) {
        ObjectSyntax scratch;  // a line that is no object may still open a block
        shape_known_ = false;
        recover_object(scratch);
      }
    }
  }

  // An object whose first line has an error is dropped, but a block it opens is still read (into the
  // dropped object) so that its statements' errors are reported and its '}' does not close the scene.
  void recover_object(ObjectSyntax& dropped) {
    while (peek().kind != TokenKind::End && peek().kind != TokenKind::Eof && peek().kind != TokenKind::RBrace &&
           peek().kind != TokenKind::LBrace)
      next();
    if (peek().kind != TokenKind::LBrace) return;
    const SourceLocation open = next().location;
    close_block(dropped, open);
  }

  // The scene holds only objects.
  void scene_statement(SceneSyntax& scene) {
    const Token& kw = peek();
    if (kw.kind != TokenKind::Word) {
      diags_.error("E0801", kw.location, "expected an object, found " + describe(kw),
                   "a scene holds `object \"name\" SHAPE at X, Y, Z { ... }` lines");
      throw StatementError{};
    }
    if (kw.text != "object") {
      std::string help;
      for (const auto& k : object_keywords())
        if (kw.text == k) help = "`" + k + "` belongs in an object's block: object \"name\" SHAPE at X, Y, Z { " + k + " ... }";
      if (help.empty()) {
        const std::string guess = closest_match(kw.text, {"object"});
        help = guess.empty() ? "a scene holds `object` statements" : "did you mean `" + guess + "`?";
      }
      diags_.error("E0802", kw.location, "unknown scene statement '" + kw.text + "'", help);
      throw StatementError{};
    }
    next();
    ObjectSyntax obj;
    bool complete = false;
    try {
      complete = object(kw.location, obj);
    } catch (const StatementError&) {
      recover_object(obj);
      return;
    }
    add_object(scene, std::move(obj));
    if (complete) end_of_statement(true);
  }

  // Names are unique (messages and the compiled scene name objects by them); past the limit objects
  // are read for their errors but not kept.
  void add_object(SceneSyntax& scene, ObjectSyntax obj) {
    if (const auto it = names_.find(obj.name); it != names_.end()) {
      auto& d = diags_.error("E0813", obj.name_location, "two objects are named \"" + obj.name + "\"",
                             "give each object a name of its own");
      d.notes.push_back({it->second, "the first is named here"});
    } else {
      names_.emplace(obj.name, obj.name_location);
    }
    if (scene.objects.size() < kMaxSceneObjects) {
      scene.objects.push_back(std::move(obj));
    } else if (!over_limit_) {
      over_limit_ = true;
      diags_.error("E0809", obj.location, "more than " + std::to_string(kMaxSceneObjects) + " objects in one scene",
                   "split the scene, or describe a large surface as one object with a texture");
    }
  }

  // object := 'object' STRING shape 'at' LENGTH ',' LENGTH ',' LENGTH ['{' (object_stmt? End)* '}']
  // False if its block was not closed: the next object's line follows, with nothing more to check.
  bool object(const SourceLocation& keyword, ObjectSyntax& obj) {
    obj.location = keyword;
    shape_known_ = false;
    if (peek().kind != TokenKind::String) {
      diags_.error("E0831", peek().location, "expected the object's name as a quoted string, found " + describe(peek()),
                   "write object \"ball\" sphere radius 50 mm at 0 mm, 60 mm, 0 mm");
      throw StatementError{};
    }
    obj.name = peek().text;
    obj.name_location = next().location;
    if (obj.name.find_first_not_of(" \t") == std::string::npos) {
      diags_.error("E0808", obj.name_location, "the object has an empty name",
                   "name it: messages and the compiled scene call it by its name");
      throw StatementError{};
    }
    shape(obj);
    position(obj);
    if (peek().kind != TokenKind::LBrace) return true;
    const SourceLocation open = next().location;
    return close_block(obj, open);
  }

  // '{' (object_stmt? End)* '}' after its '{': true if the '}' is there. The block ends at '}', at the
  // end of the file, or at a line that starts with `object` (its '}' was left out).
  bool close_block(ObjectSyntax& obj, const SourceLocation& open) {
    while (true) {
      skip_ends();
      const Token& t = peek();
      if (t.kind == TokenKind::RBrace) {
        next();
        return true;
      }
      if (t.kind == TokenKind::Eof || (t.kind == TokenKind::Word && t.text == "object")) {
        diags_.error("E0803", open, obj.name.empty() ? "the object's block is not closed"
                                                     : "the block of object \"" + obj.name + "\" is not closed",
                     "add '}' after its last statement");
        return false;
      }
      try {
        object_statement(obj);
        end_of_statement(false);
      } catch (const StatementError&) {
        skip_statement();
      }
    }
  }

  // A statement ends at a line end, ';', '}' or the end of the file.
  void end_of_statement(bool object_line) {
    const Token& t = peek();
    if (t.kind == TokenKind::End || t.kind == TokenKind::Eof || t.kind == TokenKind::RBrace) return;
    std::string help = "put one statement on each line, or separate statements with ';'";
    if (object_line && t.kind == TokenKind::Word && (t.text == "inside" || t.text == "facing"))
      help = "write `" + t.text + "` after the shape's sizes, before `at`";
    diags_.error("E0834", t.location, "unexpected " + describe(t) + " after the statement", help);
    throw StatementError{};
  }

  // Past a statement's error: to its end, stepping over any block opened in it (braces counted, no
  // recursion, so a line of a million '{' is no deeper than one).
  void skip_statement() {
    std::size_t depth = 0;
    while (peek().kind != TokenKind::Eof) {
      const TokenKind k = peek().kind;
      if (depth == 0 && (k == TokenKind::End || k == TokenKind::RBrace)) return;
      if (k == TokenKind::LBrace) ++depth;
      if (k == TokenKind::RBrace) --depth;
      next();
    }
  }

  // shape := 'sphere' 'radius' LENGTH
  //        | 'box' LENGTH 'x' LENGTH 'x' LENGTH ['inside']
  //        | 'plane' LENGTH 'x' LENGTH ['facing' SIDE]
  void shape(ObjectSyntax& obj) {
    const Token& t = peek();
    if (t.kind != TokenKind::Word) {
      diags_.error("E0807", t.location, "expected the object's shape, found " + describe(t),
                   "write sphere radius R, box W x H x D or plane W x D");
      throw StatementError{};
    }
    obj.shape_location = t.location;
    shape_known_ = t.text == "sphere" || t.text == "box" || t.text == "plane";
    if (t.text == "sphere") {
      next();
      obj.shape = ShapeKind::Sphere;
      if (!at_word("radius")) {
        diags_.error("E0807", peek().location, "expected `radius` after `sphere`, found " + describe(peek()),
                     "write sphere radius 50 mm");
        throw StatementError{};
      }
      next();
      obj.radius = positive(quantity(Dimension::Length, "the sphere's radius"), "the sphere's radius");
    } else if (t.text == "box") {
      next();
      obj.shape = ShapeKind::Box;
      static const char* const what[] = {"the box's width (x)", "the box's height (y)", "the box's depth (z)"};
      for (std::size_t i = 0; i < 3; ++i) {
        if (i > 0) times(what[i], "a box has three sizes: box 80 mm x 40 mm x 80 mm (width x height x depth)");
        obj.size[i] = positive(quantity(Dimension::Length, what[i]), what[i]);
      }
      if (at_word("inside")) {
        next();
        obj.inside = true;
      }
    } else if (t.text == "plane") {
      next();
      obj.shape = ShapeKind::Plane;
      obj.size[0] = positive(quantity(Dimension::Length, "the plane's width"), "the plane's width");
      times("the plane's depth", "a plane has two sizes: plane 300 mm x 300 mm (width x depth)");
      obj.size[2] = positive(quantity(Dimension::Length, "the plane's depth"), "the plane's depth");
      if (at_word("facing")) {
        next();
        obj.facing_location = peek().location;
        obj.facing = side("after `facing`");
      }
    } else {
      const std::string guess = closest_match(t.text, shape_words());
      diags_.error("E0807", t.location, "unknown shape '" + t.text + "'",
                   guess.empty() ? "the shapes are sphere, box and plane" : "did you mean `" + guess + "`?");
      throw StatementError{};
    }
    other_shapes_option(obj);
  }

  // `inside` and `facing` after a shape they do not belong to.
  void other_shapes_option(const ObjectSyntax& obj) {
    const Token& t = peek();
    if (at_word("inside") && obj.shape != ShapeKind::Box) {
      diags_.error("E0811", t.location, std::string("only a box can be felt from inside, not a ") + shape_word(obj.shape),
                   obj.shape == ShapeKind::Plane ? "a plane is felt from the side it faces: turn it with `facing SIDE`"
                                                 : "for a room, use a box: box W x H x D inside");
      throw StatementError{};
    }
    if (at_word("facing") && obj.shape != ShapeKind::Plane) {
      diags_.error("E0811", t.location, std::string("only a plane has a facing, not a ") + shape_word(obj.shape),
                   obj.shape == ShapeKind::Box ? "a box's faces each take a material: material \"M\" on top"
                                               : "a sphere faces every way; remove `facing`");
      throw StatementError{};
    }
  }

  // The 'x' between two sizes.
  void times(const char* what, const char* help) {
    if (!at_word("x")) {
      diags_.error("E0807", peek().location, std::string("expected 'x' and ") + what + ", found " + describe(peek()), help);
      throw StatementError{};
    }
    next();
  }

  // 'at' LENGTH ',' LENGTH ',' LENGTH   -- the centre, in the scene's frame (y up, z toward the user)
  void position(ObjectSyntax& obj) {
    if (!at_word("at")) {
      diags_.error("E0832", peek().location, "expected `at` and the object's centre, found " + describe(peek()),
                   "write at X, Y, Z with units, e.g. at 0 mm, 60 mm, 0 mm (y up, z toward you)");
      throw StatementError{};
    }
    next();
    obj.x = quantity(Dimension::Length, "the centre's x");
    comma("between the centre's x and y");
    obj.y = quantity(Dimension::Length, "the centre's y");
    comma("between the centre's y and z");
    obj.z = quantity(Dimension::Length, "the centre's z");
    obj.at_location = obj.x.location;
    if (obj.z.location.line == obj.x.location.line)
      obj.at_location.length = obj.z.location.column + obj.z.location.length - obj.x.location.column;
  }

  void comma(const char* where) {
    if (peek().kind != TokenKind::Comma) {
      diags_.error("E0832", peek().location, std::string("expected ',' ") + where + ", found " + describe(peek()),
                   "write at X, Y, Z, e.g. at 0 mm, 60 mm, 0 mm");
      throw StatementError{};
    }
    next();
  }

  // object_stmt := 'material' STRING ['on' SIDE] | 'stiffness' STIFFNESS | 'damping' DAMPING
  //              | 'friction' NUMBER [NUMBER] | 'texture' 'size' LENGTH ['x' LENGTH]
  //              | 'texture' 'relief' LENGTH ['only']
  void object_statement(ObjectSyntax& obj) {
    const Token& kw = peek();
    if (kw.kind != TokenKind::Word) {
      diags_.error("E0801", kw.location, "expected an object statement, found " + describe(kw),
                   "an object's block holds material, stiffness, damping, friction, texture size and texture relief lines");
      throw StatementError{};
    }
    next();
    if (kw.text == "material") {
      material(obj, kw);
    } else if (kw.text == "stiffness") {
      // Checked before it is kept: a statement with an error leaves nothing in the object.
      once(obj.stiffness ? &obj.stiffness->location : nullptr, kw, "stiffness");
      const Quantity k = quantity(Dimension::Stiffness, "the stiffness");
      if (k.si <= 0) out_of_range(k, "the stiffness must be positive", "a surface pushes back: give a stiffness such as 800 N/m");
      obj.stiffness = k;
    } else if (kw.text == "damping") {
      once(obj.damping ? &obj.damping->location : nullptr, kw, "damping");
      const Quantity b = quantity(Dimension::Damping, "the damping");
      if (b.si < 0) out_of_range(b, "the damping must not be negative", "give 0 N*s/m or more");
      obj.damping = b;
    } else if (kw.text == "friction") {
      friction(obj, kw);
    } else if (kw.text == "texture") {
      texture(obj, kw);
    } else {
      const std::string guess = closest_match(kw.text, object_keywords());
      diags_.error("E0802", kw.location, "unknown object statement '" + kw.text + "'",
                   guess.empty() ? "an object holds material, stiffness, damping, friction, texture size and texture relief lines"
                                 : "did you mean `" + guess + "`?");
      throw StatementError{};
    }
  }

  // A statement given before in this object: E0805, pointing at the first.
  void once(const SourceLocation* first, const Token& kw, const char* what) {
    if (!first) return;
    auto& d = diags_.error("E0805", kw.location, std::string("the object's ") + what + " is given twice",
                           "keep one of the two lines");
    d.notes.push_back({*first, std::string("the ") + what + " is first given here"});
    throw StatementError{};
  }

  [[noreturn]] void out_of_range(const Quantity& q, const std::string& what, const char* help) {
    diags_.error("E0812", q.location, what + ", not " + q.text(), help);
    throw StatementError{};
  }

  // 'material' STRING ['on' SIDE]   -- without a side: every surface not given its own
  void material(ObjectSyntax& obj, const Token& kw) {
    SurfaceSyntax s;
    s.location = kw.location;
    if (peek().kind != TokenKind::String) {
      diags_.error("E0831", peek().location, "expected the material as a quoted string, found " + describe(peek()),
                   "write material \"corduroy\" (a library name), material \"roughness 0.4; grating period 2 mm\" or "
                   "material \"stone.hmat\"");
      throw StatementError{};
    }
    s.material = peek().text;
    s.material_location = next().location;
    if (s.material.find_first_not_of(" \t") == std::string::npos) {
      diags_.error("E0808", s.material_location, "the object has an empty material",
                   "name a library entry (\"corduroy\"), write statements (\"roughness 0.4; grating period 2 mm\") "
                   "or give a .hmat file");
      throw StatementError{};
    }
    if (at_word("on")) {
      if (shape_known_ && obj.shape != ShapeKind::Box) {
        diags_.error("E0811", peek().location, std::string("only a box has sides, not a ") + shape_word(obj.shape),
                     obj.shape == ShapeKind::Plane ? "a plane has one surface: remove `on ...` (turn the plane with `facing SIDE`)"
                                                   : "a sphere has one surface: remove `on ...`");
        throw StatementError{};
      }
      next();
      s.side = side("after `on`");
    }
    for (const auto& other : obj.surfaces) {
      if (other.side != s.side) continue;
      auto& d = diags_.error("E0805", kw.location,
                             s.side ? std::string("the object's ") + side_name(*s.side) + " side is given a material twice"
                                    : std::string("the object is given a material for all its surfaces twice"),
                             s.side ? "keep one of the two lines" : "keep one, or give the other a side: material \"M\" on top");
      d.notes.push_back({other.location, "the first is given here"});
      throw StatementError{};
    }
    obj.surfaces.push_back(std::move(s));
  }

  // 'friction' NUMBER [NUMBER]   -- static, then kinetic; one number is both
  void friction(ObjectSyntax& obj, const Token& kw) {
    once(obj.static_friction ? &obj.friction_location : nullptr, kw, "friction");
    const Token& first = peek();
    const double s = coefficient("the static friction");
    const Token& second = peek();
    const double k = second.kind == TokenKind::Number ? coefficient("the kinetic friction") : s;
    if (s < 0 || k < 0) {
      diags_.error("E0812", (s < 0 ? first : second).location, "a friction coefficient must not be negative",
                   "give 0 (no friction) or more, e.g. friction 0.5 0.3");
      throw StatementError{};
    }
    if (k > s) {
      diags_.error("E0812", second.location,
                   "the kinetic friction " + second.text + " is above the static friction " + first.text,
                   "a surface holds at least as hard as it drags: friction " + second.text + " " + first.text +
                       " (static first)");
      throw StatementError{};
    }
    obj.static_friction = s;
    obj.kinetic_friction = k;
    obj.friction_location = kw.location;
  }

  // A friction coefficient: a plain number.
  double coefficient(const char* what) {
    const Token& n = peek();
    if (n.kind != TokenKind::Number) {
      diags_.error("E0833", n.location, std::string("expected ") + what + " (a plain number), found " + describe(n),
                   "for example friction 0.5 0.3 (static, kinetic)");
      throw StatementError{};
    }
    next();
    if (peek().kind == TokenKind::Word && schema::find_unit(peek().text)) {
      diags_.error("E0205", peek().location, std::string(what) + " is a plain number and takes no unit",
                   "write it without a unit, e.g. friction 0.5 0.3");
      throw StatementError{};
    }
    if (!std::isfinite(n.number) ||
        (n.number != 0 && (std::abs(n.number) < kLeastQuantitySI || std::abs(n.number) > kGreatestQuantitySI))) {
      diags_.error("E0103", n.location, "number out of range '" + n.text + "': " + what + " must be 0 or between 1e-12 and 1e12",
                   "use a coefficient a hand could feel, for example 0.5");
      throw StatementError{};
    }
    return n.number;
  }

  // 'texture' ('size' ... | 'relief' ...)
  void texture(ObjectSyntax& obj, const Token& kw) {
    if (at_word("size")) {
      next();
      texture_size(obj, kw);
    } else if (at_word("relief")) {
      next();
      texture_relief(obj, kw);
    } else {
      diags_.error("E0801", peek().location, "expected `size` or `relief` after `texture`, found " + describe(peek()),
                   "write texture size 40 mm (x 20 mm), or texture relief 0.5 mm (only)");
      throw StatementError{};
    }
  }

  // 'texture' 'size' LENGTH ['x' LENGTH]   -- metres of surface per unit of u and v; H absent: W
  void texture_size(ObjectSyntax& obj, const Token& kw) {
    once(obj.texture_width ? &obj.texture_location : nullptr, kw, "texture size");
    const Quantity w = positive(quantity(Dimension::Length, "the texture's width"), "the texture's width");
    std::optional<Quantity> h;
    if (at_word("x")) {
      next();
      h = positive(quantity(Dimension::Length, "the texture's height"), "the texture's height");
    }
    obj.texture_width = w;
    obj.texture_height = h;
    obj.texture_location = kw.location;
  }

  // 'texture' 'relief' LENGTH ['only']   -- the surface carved along its normal by its texture, at
  // most LENGTH deep (Minsky 1995, 7.7.2); `only`: without the lateral-force texture
  void texture_relief(ObjectSyntax& obj, const Token& kw) {
    once(obj.relief_depth ? &obj.relief_location : nullptr, kw, "texture relief");
    const Quantity d = quantity(Dimension::Length, "the relief's depth");
    if (!(d.si > 0)) {
      diags_.error("E0806", d.location, "the relief's depth must be positive, not " + d.text(),
                   "give the depth of the texture's valleys below its hills, e.g. texture relief 0.5 mm");
      throw StatementError{};
    }
    if (d.si > shapes::scene_limits::kMaxReliefDepth_m) {
      diags_.error("E0814", d.location, "a relief of " + d.text() + " is deeper than 10 mm",
                   "a relief is a texture pressed into the surface: give 10 mm or less, or model deeper features as shapes");
      throw StatementError{};
    }
    bool only = false;
    if (at_word("only")) {
      next();
      only = true;
    }
    obj.relief_depth = d;
    obj.relief_only = only;
    obj.relief_location = kw.location;
  }

  // SIDE := 'top' | 'bottom' | 'right' | 'left' | 'front' | 'back'
  Side side(const char* after) {
    const Token& t = peek();
    if (t.kind != TokenKind::Word) {
      diags_.error("E0810", t.location, std::string("expected a side ") + after + ", found " + describe(t),
                   "the sides are top, bottom, right, left, front and back (+y, -y, +x, -x, +z, -z)");
      throw StatementError{};
    }
    for (const Side s : kSides)
      if (t.text == side_name(s)) {
        next();
        return s;
      }
    const std::string guess = closest_match(t.text, side_words());
    diags_.error("E0810", t.location, "unknown side '" + t.text + "'",
                 guess.empty() ? "the sides are top, bottom, right, left, front and back (+y, -y, +x, -x, +z, -z)"
                               : "did you mean `" + guess + "`?");
    throw StatementError{};
  }

  Quantity positive(Quantity q, const char* what) {
    if (q.si > 0) return q;
    diags_.error("E0806", q.location, std::string(what) + " must be positive, not " + q.text(),
                 "give a size greater than zero");
    throw StatementError{};
  }

  // quantity := NUMBER UNIT, UNIT of the statement's dimension (the material language's unit rules,
  // E0203-E0205, and its bounds, E0103)
  Quantity quantity(Dimension dim, const char* what) {
    const std::string units = schema::units_of(dim);
    const std::string dim_name(schema::dimension_name(dim));
    const Token& n = peek();
    if (n.kind != TokenKind::Number) {
      diags_.error("E0833", n.location, std::string("expected ") + what + " (a number and a " + dim_name + " unit), found " + describe(n),
                   "for example " + example(dim));
      throw StatementError{};
    }
    next();
    const Token& u = peek();
    const auto def = u.kind == TokenKind::Word ? schema::find_unit(u.text) : std::nullopt;
    if (!def) {
      std::vector<std::string> names;
      for (const auto& x : schema::all_units()) names.emplace_back(x.name);
      const std::string guess = u.kind == TokenKind::Word ? closest_match(u.text, names) : std::string();
      // A word nothing like a unit (`at`, `x`) means the unit was left out.
      if (guess.empty()) {
        diags_.error("E0203", n.location, "`" + n.text + "` has no unit; " + what + " is a " + dim_name,
                     "add a unit: " + units + " (e.g. " + example(dim) + ")");
      } else {
        diags_.error("E0204", u.location, "unknown unit '" + u.text + "'", "did you mean `" + guess + "`?");
      }
      throw StatementError{};
    }
    if (def->dimension != dim) {
      diags_.error("E0205", u.location, "`" + u.text + "` is a " + std::string(schema::dimension_name(def->dimension)) +
                   " unit, but " + what + " is a " + dim_name, "use one of: " + units);
      throw StatementError{};
    }
    next();
    const double si = n.number * def->to_si;
    if (!std::isfinite(n.number) || !std::isfinite(si) ||
        (si != 0 && (std::abs(si) < kLeastQuantitySI || std::abs(si) > kGreatestQuantitySI))) {
      diags_.error("E0103", n.location,
                   "number out of range '" + n.text + " " + u.text + "': " + what + " must be 0 or between 1e-12 and 1e12 " +
                       std::string(schema::si_unit_name(dim)),
                   "use a value a hand could feel, for example " + example(dim));
      throw StatementError{};
    }
    SourceLocation span = n.location;
    span.length = u.location.line == n.location.line ? u.location.column + u.location.length - n.location.column
                                                      : n.location.length;
    return Quantity{n.number, u.text, si, span};
  }

  std::shared_ptr<const SourceFile> file_;
  Diagnostics& diags_;
  std::map<std::string, SourceLocation> names_;  // each object's name, where first given
  bool over_limit_ = false;
  // Whether the object being read named a shape it has: an object dropped before its shape was read
  // has its block read with no shape to check `on SIDE` against.
  bool shape_known_ = false;
};

}  // namespace

bool is_scene_path(const std::string& path) { return std::filesystem::path(path).extension() == ".hsc"; }

SceneSyntax parse_scene(const std::vector<compiler::Token>& tokens, std::shared_ptr<const compiler::SourceFile> file,
                        compiler::Diagnostics& diags) {
  if (tokens.empty() || tokens.back().kind != TokenKind::Eof) throw compiler::InternalError("scene tokens must end with Eof");
  return SceneParser(tokens, std::move(file), diags).file();
}

const char* side_name(Side side) {
  switch (side) {
    case Side::Top: return "top";
    case Side::Bottom: return "bottom";
    case Side::Right: return "right";
    case Side::Left: return "left";
    case Side::Front: return "front";
    case Side::Back: return "back";
  }
  return "?";
}

}  // namespace sandpaper::scenes
