// The statements that set what a material feels like: perceptual words, textures, force laws and
// the quantities they take.
#include "parser_impl.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/schema/diagnostic_codes.hpp"
#include "sandpaper/schema/force_laws.hpp"

namespace sandpaper::compiler::parse_detail {

// roughness := 'roughness' (NUMBER | LEVEL)
RoughnessStmt Parser::roughness() {
  const Token& t = peek();
  if (t.kind == TokenKind::Number) {
    next();
    if (pos_ < toks_.size() && peek().kind == TokenKind::Word && schema::find_unit(peek().text)) {
      diags_.error("E0205", peek().location, "roughness is a ratio-scale number and takes no unit",
                   "write roughness 0.6, or give a force with amplitude (e.g. grating ... amplitude 2 N)");
      throw StatementError{};
    }
    return RoughnessStmt{t.number, {}, t.location};
  }
  if (t.kind == TokenKind::Word) {
    next();
    return RoughnessStmt{std::nullopt, t.text, t.location};
  }
  diags_.error("E0215", t.location, std::string("expected a roughness number or level, found ") + describe(t),
               "write roughness 0.6 (ratio scale, 1 = 3.746 N) or roughness coarse");
  throw StatementError{};
}

// percept := ('viscosity' | 'stickiness' | 'slipperiness' | 'softness' | 'springiness' | 'bumpiness')
//            (NUMBER | LEVEL)
PerceptStmt Parser::percept(const PerceptWord& w) {
  const Token& t = peek();
  if (t.kind == TokenKind::Number) {
    next();
    if (peek().kind == TokenKind::Word && schema::find_unit(peek().text)) {
      diags_.error("E0205", peek().location, std::string(w.word) + " is a ratio-scale number and takes no unit",
                   std::string("write ") + w.word + " " + t.text + ", or give it physically: " + w.physical);
      throw StatementError{};
    }
    if (!std::isfinite(t.number)) {
      diags_.error("E0103", t.location, "number out of range '" + t.text + "'", "use a finite number");
      throw StatementError{};
    }
    return PerceptStmt{w.word, t.number, {}, t.location};
  }
  if (t.kind == TokenKind::Word) {
    next();
    return PerceptStmt{w.word, std::nullopt, t.text, t.location};
  }
  diags_.error("E0215", t.location, std::string("expected a ") + w.word + " number or level, found " + describe(t),
               std::string("write ") + w.word + " 0.5 (a ratio-scale number, 1 at the top of its map), or give it "
                   "physically: " + w.physical);
  throw StatementError{};
}

// grating := 'grating' ( 'period' LENGTH | 'hill' FRACTION | 'amplitude' FORCE | 'orientation' ANGLE
//                      | 'smoothing' LENGTH )+
// Every option may be left out (a file `like` a grating overrides it parameter by parameter), but
// not all of them; the resolver asks for the period when nothing is inherited.
GratingStmt Parser::grating() {
  GratingStmt g;
  g.location = toks_[pos_ - 1].location;
  static const std::vector<std::string> opts{"period", "hill", "amplitude", "orientation", "smoothing"};
  if (peek().kind != TokenKind::Word) {
    diags_.error("E0216", peek().location, std::string("expected `period`, found ") + describe(peek()),
                 "write grating period 2.5 mm [hill 50%] [amplitude 2 N] [orientation 0 deg]");
    throw StatementError{};
  }
  while (peek().kind == TokenKind::Word) {
    const Token& o = next();
    if (o.text == "period") set_once(g.period, o, Dimension::Length, "the grating period");
    else if (o.text == "hill") set_once(g.hill, o, Dimension::Fraction, "the hill fraction");
    else if (o.text == "amplitude") set_once(g.amplitude, o, Dimension::Force, "the force amplitude");
    else if (o.text == "orientation") set_once(g.orientation, o, Dimension::Angle, "the grating orientation");
    else if (o.text == "smoothing") set_once(g.smoothing, o, Dimension::Length, "the smoothing");
    else unknown_option("grating", o, opts);
  }
  return g;
}

// heightmap := 'heightmap' STRING 'size' LENGTH ['x' LENGTH]
//              ( 'smoothing' LENGTH | 'amplitude' FORCE | 'repeat' | 'channel' (NAME | STRING)
//              | 'sampling' LENGTH | 'invert' | 'depth' LENGTH | 'press' FORCE )*
HeightmapStmt Parser::heightmap() {
  HeightmapStmt h;
  if (peek().kind != TokenKind::String) {
    diags_.error("E0214", peek().location, std::string("expected the image file as a quoted path, found ") + describe(peek()),
                 "write heightmap \"gravel.png\" size 80 mm");
    throw StatementError{};
  }
  h.path = peek().text;
  h.path_location = next().location;
  if (!(peek().kind == TokenKind::Word && peek().text == "size")) {
    diags_.error("E0216", peek().location, std::string("expected `size`, found ") + describe(peek()),
                 "an image has no physical scale: say how large it is, e.g. size 80 mm or size 80 mm x 60 mm");
    throw StatementError{};
  }
  next();
  h.width = quantity(Dimension::Length, "the image width");
  if (peek().kind == TokenKind::Word && peek().text == "x") {
    next();
    h.height = quantity(Dimension::Length, "the image height");
  }
  static const std::vector<std::string> opts{"smoothing", "amplitude", "repeat", "channel", "sampling",
                                             "invert",    "depth",     "press"};
  bool channel_seen = false;
  while (peek().kind == TokenKind::Word) {
    const Token& o = next();
    if (o.text == "smoothing") set_once(h.smoothing, o, Dimension::Length, "the smoothing");
    else if (o.text == "amplitude") set_once(h.amplitude, o, Dimension::Force, "the force amplitude");
    else if (o.text == "repeat") h.repeat = true;
    else if (o.text == "invert") h.invert = true;
    else if (o.text == "sampling") set_once(h.sampling, o, Dimension::Length, "the sampling");
    else if (o.text == "depth") set_once(h.depth, o, Dimension::Length, "the relief depth");
    else if (o.text == "press") set_once(h.press, o, Dimension::Force, "the downward force");
    else if (o.text == "channel") {
      if (channel_seen) {
        diags_.error("E0206", o.location, "`channel` is given twice in one statement", "keep one of them");
        throw StatementError{};
      }
      channel_seen = true;
      if (peek().kind != TokenKind::Word && peek().kind != TokenKind::String) {
        diags_.error("E0217", peek().location, std::string("expected a channel name, found ") + describe(peek()),
                     "write channel R, or channel \"Z\" for a name that is not a word");
        throw StatementError{};
      }
      if (peek().text.empty()) {
        diags_.error("E0217", peek().location, "the channel name is empty",
                     "name a channel, e.g. channel R, or leave `channel` out for the luminance rule");
        throw StatementError{};
      }
      h.channel = peek().text;
      h.channel_location = next().location;
    } else unknown_option("heightmap", o, opts);
  }
  return h;
}

// law      := ('force' | 'physics') LAW_NAME (PARAM value)*
// value    := NUMBER UNIT | NUMBER | 'x' | 'y' | 'xy'     -- as schema/force_laws.hpp declares PARAM
LawStmt Parser::law(schema::LawFamily family) {
  const std::string keyword(schema::family_keyword(family));
  std::vector<std::string> names;
  for (const auto& l : schema::all_laws())
    if (l.family == family) names.emplace_back(l.name);
  const Token& n = peek();
  if (n.kind != TokenKind::Word) {
    diags_.error("E0217", n.location, "expected the name of a " + keyword + " law, found " + describe(n),
                 "one of: " + join(names));
    throw StatementError{};
  }
  const schema::LawDef* def = schema::find_law(family, n.text);
  if (!def) {
    std::string guess = closest_match(n.text, names);
    diags_.error("E0211", n.location, "unknown " + keyword + " law '" + n.text + "'",
                 guess.empty() ? keyword + " laws are: " + join(names) : "did you mean `" + guess + "`?");
    throw StatementError{};
  }
  next();
  LawStmt out{family == schema::LawFamily::Physics, std::string(def->name), n.location, {}};
  std::vector<std::string> params;
  for (const auto& p : def->params) params.emplace_back(p.name);
  while (peek().kind == TokenKind::Word) {
    const Token& o = next();
    const schema::LawParam* param = schema::find_param(*def, o.text);
    if (!param) {
      if (params.empty()) {
        diags_.error("E0209", o.location, keyword + " " + out.name + " takes no parameters", "remove '" + o.text + "'");
        throw StatementError{};
      }
      unknown_option((keyword + " " + out.name).c_str(), o, params);
    }
    for (const auto& a : out.args)
      if (a.name == o.text) {
        diags_.error("E0206", o.location, "`" + o.text + "` is given twice in one statement", "keep one of them");
        throw StatementError{};
      }
    LawArg arg{o.text, std::nullopt, {}, o.location};
    const std::string what = "the " + out.name + " " + o.text;
    if (param->kind == schema::LawParamKind::Quantity) {
      arg.quantity = quantity(param->dimension, what.c_str());
    } else if (param->kind == schema::LawParamKind::Number) {
      const Token& v = peek();
      if (v.kind != TokenKind::Number) {
        diags_.error("E0215", v.location, "expected " + what + " (a plain number), found " + describe(v), "for example 0.3");
        throw StatementError{};
      }
      next();
      arg.quantity = Quantity{v.number, "", v.number, v.location};
    } else {
      const Token& v = peek();
      if (v.kind != TokenKind::Word || (v.text != "x" && v.text != "y" && v.text != "xy")) {
        diags_.error("E0217", v.location, "expected the axes x, y or xy, found " + describe(v),
                     "write axes x (force along x only), axes y, or axes xy (a grid)");
        throw StatementError{};
      }
      arg.word = next().text;
    }
    out.args.push_back(std::move(arg));
  }
  return out;
}

// energy := 'energy' 'budget' ENERGY ['refill' POWER]
EnergyStmt Parser::energy() {
  if (!(peek().kind == TokenKind::Word && peek().text == "budget")) {
    diags_.error("E0216", peek().location, std::string("expected `budget`, found ") + describe(peek()),
                 "write energy budget 50 mJ [refill 10 mW]");
    throw StatementError{};
  }
  next();
  EnergyStmt e{quantity(Dimension::Energy, "the energy budget"), std::nullopt};
  static const std::vector<std::string> opts{"refill"};
  while (peek().kind == TokenKind::Word) {
    const Token& o = next();
    if (o.text == "refill") set_once(e.refill, o, Dimension::Power, "the refill power");
    else unknown_option("energy", o, opts);
  }
  return e;
}

// A word that names a force law (`friction`, `nap-friction`): people write the physics they mean
// as a statement, and the law is how the language says it.
const schema::LawDef* Parser::law_named_by(const std::string& word) {
  std::string w;
  for (char c : word)
    if (c != '-' && c != '_') w += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const auto& law : schema::all_laws()) {
    std::string n;
    for (char c : law.name) n += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (n == w) return &law;
  }
  return nullptr;
}

std::string Parser::law_statement_help(const schema::LawDef& law) {
  const std::string keyword = law.family == schema::LawFamily::Physics ? "physics" : "force";
  std::string required;
  for (const auto& p : law.params)
    if (p.required) required += (required.empty() ? "" : ", ") + std::string(p.name);
  std::string help = "'" + std::string(law.name) + "' is a force law: write `" + keyword + " " + std::string(law.name) +
                     "` with " + required;
  // Coulomb friction is the one people reach for by name; show it whole.
  if (law.name == "Friction") help += ", e.g. `physics Friction static 0.6 kinetic 0.4 press 1 N`";
  return help + " (schema/LANGUAGE.md, \"Force laws\")";
}

std::string Parser::join(const std::vector<std::string>& xs) {
  std::string out;
  for (const auto& x : xs) out += (out.empty() ? "" : ", ") + x;
  return out;
}

// pattern := 'pattern' KIND pattern_option*
// KIND := 'bars' | 'grid' | 'perlin' | 'noise' | 'stripes'
// pattern_option := 'valley' LENGTH | 'hill' LENGTH | 'offset' LENGTH | 'feature' LENGTH | 'pixel' LENGTH
//                 | 'kernel' NUMBER | 'refilter' NUMBER | 'seed' NUMBER | 'count' NUMBER | 'amplitude' FORCE
// Which options each kind takes, and which it needs: `kinds` below (schema/LANGUAGE.md).
PatternStmt Parser::pattern() {
  struct KindRule { const char* kind; std::vector<std::string> options; std::vector<std::string> required; const char* example; };
  static const std::vector<KindRule> kinds{
      {"bars", {"valley", "hill", "kernel", "refilter", "pixel", "amplitude"}, {"valley", "hill"},
       "pattern bars valley 5.55 mm hill 7.4 mm kernel 2"},
      {"grid", {"valley", "hill", "offset", "kernel", "refilter", "pixel", "amplitude"}, {"valley", "hill"},
       "pattern grid valley 5.55 mm hill 7.4 mm kernel 2"},
      {"perlin", {"feature", "seed", "pixel", "amplitude"}, {"feature"}, "pattern perlin feature 5.55 mm seed 1"},
      {"noise", {"feature", "seed", "pixel", "amplitude"}, {}, "pattern noise seed 1"},
      {"stripes", {"count", "kernel", "pixel", "amplitude"}, {"count"}, "pattern stripes count 2"},
  };
  const Token& k = peek();
  const KindRule* rule = nullptr;
  if (k.kind == TokenKind::Word)
    for (const auto& r : kinds)
      if (k.text == r.kind) rule = &r;
  if (!rule) {
    std::vector<std::string> names;
    for (const auto& r : kinds) names.emplace_back(r.kind);
    std::string guess = k.kind == TokenKind::Word ? closest_match(k.text, names) : "";
    diags_.error("E0217", k.location, std::string("expected a pattern kind, found ") + describe(k),
                 guess.empty() ? "pattern kinds are: bars, grid, perlin, noise, stripes" : "did you mean `" + guess + "`?");
    throw StatementError{};
  }
  PatternStmt p;
  p.kind = k.text;
  p.kind_location = next().location;
  const std::string stmt = "pattern " + p.kind;
  while (peek().kind == TokenKind::Word) {
    const Token& o = next();
    if (std::find(rule->options.begin(), rule->options.end(), o.text) == rule->options.end())
      unknown_option(stmt.c_str(), o, rule->options);
    if (o.text == "valley") set_once(p.valley, o, Dimension::Length, "the valley width");
    else if (o.text == "hill") set_once(p.hill, o, Dimension::Length, "the hill width");
    else if (o.text == "offset") set_once(p.offset, o, Dimension::Length, "the row offset");
    else if (o.text == "feature") set_once(p.feature, o, Dimension::Length, "the feature size");
    else if (o.text == "pixel") set_once(p.pixel, o, Dimension::Length, "the pixel pitch");
    else if (o.text == "amplitude") set_once(p.amplitude, o, Dimension::Force, "the force amplitude");
    else if (o.text == "kernel") set_once(p.kernel, o, "the Gaussian kernel size in pixels", "kernel 2");
    else if (o.text == "refilter") set_once(p.refilter, o, "the second pass's kernel size in pixels", "refilter 1");
    else if (o.text == "seed") set_once(p.seed, o, "the random seed", "seed 1");
    else if (o.text == "count") set_once(p.count, o, "the number of stripes", "count 2");
  }
  for (const auto& req : rule->required) {
    bool have = (req == "valley" && p.valley) || (req == "hill" && p.hill) || (req == "feature" && p.feature) ||
                (req == "count" && p.count);
    if (!have) {
      diags_.error("E0219", p.kind_location, stmt + " needs `" + req + "`", std::string("for example ") + rule->example);
      throw StatementError{};
    }
  }
  return p;
}

// quantize := 'quantize' NUMBER ('bit' | 'bits')
QuantizeStmt Parser::quantize() {
  QuantizeStmt q{plain_number("the number of bits", "quantize 8 bit")};
  if (!(peek().kind == TokenKind::Word && (peek().text == "bit" || peek().text == "bits"))) {
    diags_.error("E0216", peek().location, std::string("expected `bit` after the number of bits, found ") + describe(peek()),
                 "write quantize 8 bit");
    throw StatementError{};
  }
  next();
  return q;
}

// A number that takes no unit: a count, a seed, a kernel size in pixels.
PlainNumber Parser::plain_number(const char* what, const char* example_text) {
  const Token& n = peek();
  if (n.kind != TokenKind::Number) {
    diags_.error("E0215", n.location, std::string("expected ") + what + " (a plain number), found " + describe(n),
                 std::string("for example ") + example_text);
    throw StatementError{};
  }
  next();
  if (peek().kind == TokenKind::Word && schema::find_unit(peek().text)) {
    diags_.error("E0205", peek().location, std::string(what) + " is a plain number and takes no unit",
                 std::string("write it without a unit, e.g. ") + example_text);
    throw StatementError{};
  }
  if (!std::isfinite(n.number)) {
    diags_.error("E0103", n.location, "number out of range '" + n.text + "'", "use a finite number");
    throw StatementError{};
  }
  return PlainNumber{n.number, n.text, n.location};
}

void Parser::set_once(std::optional<PlainNumber>& slot, const Token& opt, const char* what, const char* example_text) {
  if (slot) {
    diags_.error("E0206", opt.location, "`" + opt.text + "` is given twice in one statement", "keep one of them");
    throw StatementError{};
  }
  slot = plain_number(what, example_text);
}

// size := 'size' LENGTH ['x' LENGTH]
SizeStmt Parser::size() {
  SizeStmt s;
  s.width = quantity(Dimension::Length, "the patch width");
  if (peek().kind == TokenKind::Word && peek().text == "x") {
    next();
    s.height = quantity(Dimension::Length, "the patch height");
  }
  return s;
}

// quantity := NUMBER UNIT, UNIT of the dimension the statement needs
Quantity Parser::quantity(Dimension dim, const char* what) {
  const Token& n = peek();
  std::string units = schema::units_of(dim);
  if (n.kind != TokenKind::Number) {
    diags_.error("E0215", n.location, std::string("expected ") + what + " (a number and a " +
                 std::string(schema::dimension_name(dim)) + " unit), found " + describe(n),
                 "for example " + example(dim));
    throw StatementError{};
  }
  next();
  const Token& u = peek();
  if (u.kind != TokenKind::Word) {
    diags_.error("E0203", n.location, std::string("`") + n.text + "` has no unit; " + what + " is a " +
                 std::string(schema::dimension_name(dim)),
                 "add a unit: " + units + " (e.g. " + example(dim) + ")");
    throw StatementError{};
  }
  auto def = schema::find_unit(u.text);
  if (!def) {
    std::vector<std::string> names;
    for (const auto& x : schema::all_units()) names.emplace_back(x.name);
    std::string guess = closest_match(u.text, names);
    // A word nothing like a unit ("amplitude") means the unit was left out.
    if (guess.empty()) {
      diags_.error("E0203", n.location, std::string("`") + n.text + "` has no unit; " + what + " is a " +
                   std::string(schema::dimension_name(dim)),
                   "add a unit: " + units + " (e.g. " + example(dim) + ")");
      throw StatementError{};
    }
    diags_.error("E0204", u.location, "unknown unit '" + u.text + "'",
                 guess.empty() ? std::string(what) + " takes " + units : "did you mean `" + guess + "`?");
    throw StatementError{};
  }
  if (def->dimension != dim) {
    diags_.error("E0205", u.location, "`" + u.text + "` is a " + std::string(schema::dimension_name(def->dimension)) +
                 " unit, but " + what + " is a " + std::string(schema::dimension_name(dim)),
                 "use one of: " + units);
    throw StatementError{};
  }
  next();
  // Outside 1e-12 to 1e12 in SI units no quantity describes something a hand can feel, and the
  // extremes (denormals, 1e300) make the runtime's arithmetic overflow or lose all precision.
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
  span.length = u.location.column + u.location.length - n.location.column;
  if (u.location.line != n.location.line) span.length = n.location.length;
  return Quantity{n.number, u.text, n.number * def->to_si, span};
}

void Parser::set_once(std::optional<Quantity>& slot, const Token& opt, Dimension dim, const char* what) {
  if (slot) {
    diags_.error("E0206", opt.location, "`" + opt.text + "` is given twice in one statement",
                 "keep one of them");
    throw StatementError{};
  }
  slot = quantity(dim, what);
}

[[noreturn]] void Parser::unknown_option(const char* stmt, const Token& o, const std::vector<std::string>& opts) {
  std::string guess = closest_match(o.text, opts);
  std::string list;
  for (const auto& x : opts) list += (list.empty() ? "" : ", ") + x;
  diags_.error("E0209", o.location, std::string("unknown ") + stmt + " option '" + o.text + "'",
               guess.empty() ? std::string(stmt) + " takes: " + list : "did you mean `" + guess + "`?");
  throw StatementError{};
}

std::string Parser::example(Dimension d) {
  switch (d) {
    case Dimension::Length: return "2.5 mm";
    case Dimension::Force: return "1.5 N";
    case Dimension::Stiffness: return "200 N/m";
    case Dimension::Damping: return "2 N*s/m";
    case Dimension::Angle: return "30 deg";
    case Dimension::Fraction: return "50%";
    case Dimension::Mass: return "50 g";
    case Dimension::Time: return "20 ms";
    case Dimension::Energy: return "50 mJ";
    case Dimension::Power: return "10 mW";
    case Dimension::Speed: return "2 mm/s";
  }
  return "";
}

}  // namespace sandpaper::compiler::parse_detail
