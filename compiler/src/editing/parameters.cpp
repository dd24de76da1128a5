// A material's numbers as slider parameters, found in the parsed syntax (so only real statements'
// numbers count, never a digit in a comment or a string), and the one-number text edit.
#include "sandpaper/compiler/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <cstdio>

#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/compiler/workspace_parser.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::compiler {
namespace {

using schema::Dimension;

// Default slider ranges (SI) by dimension: wide enough for any material in the library, narrow
// enough that a slider's travel means something. Ranges widen to include the value written.
struct SiRange {
  double min, max;
};
SiRange default_range(Dimension d, double max_force_N) {
  switch (d) {
    case Dimension::Length: return {0.1e-3, 100e-3};
    case Dimension::Force: return {0, max_force_N};
    case Dimension::Stiffness: return {0, 2000};
    case Dimension::Damping: return {0, 20};
    case Dimension::Angle: return {0, M_PI};
    case Dimension::Fraction: return {0, 1};
    case Dimension::Mass: return {0, 0.5};
    case Dimension::Time: return {0, 2};
    case Dimension::Energy: return {0, 0.5};
    case Dimension::Power: return {0, 1};
    case Dimension::Speed: return {0, 0.05};
  }
  return {0, 1};
}

class Collector {
 public:
  Collector(const std::vector<Token>& tokens, double max_force_N) : max_force_N_(max_force_N) {
    for (const auto& t : tokens)
      if (t.kind == TokenKind::Number) number_length_[{t.location.line, t.location.column}] = t.location.length;
  }

  // A quantity with its unit; `range` (SI) overrides the dimension's default.
  void quantity(const std::string& name, const std::string& label, const std::string& layer, const Quantity& q,
                const SiRange* range = nullptr) {
    Parameter p = base(name, label, layer, q.location, q.value);
    p.unit = q.unit;
    p.si = q.si;
    const auto def = schema::find_unit(q.unit);
    const double to_si = def ? def->to_si : 1.0;
    const SiRange r = range ? *range : def ? default_range(def->dimension, max_force_N_) : SiRange{0, 100};
    finish(p, r.min / to_si, r.max / to_si);
  }

  // A unitless number (a percept, a count, a kernel in pixels).
  void plain(const std::string& name, const std::string& label, const std::string& layer, const SourceLocation& at,
             double value, double lo, double hi) {
    Parameter p = base(name, label, layer, at, value);
    p.si = value;
    finish(p, lo, hi);
  }

  std::vector<Parameter> take() { return std::move(out_); }

 private:
  Parameter base(const std::string& name, const std::string& label, const std::string& layer, const SourceLocation& at,
                 double value) {
    Parameter p;
    // A second statement of the same kind (two gratings) gets "#2", so every name stays unique.
    const int n = ++seen_[name];
    p.name = n == 1 ? name : name + "#" + std::to_string(n);
    p.label = label;
    p.layer = layer;
    p.value = value;
    p.line = at.line;
    p.column = at.column;
    const auto it = number_length_.find({at.line, at.column});
    p.length = it == number_length_.end() ? 0 : it->second;
    return p;
  }
  void finish(Parameter& p, double lo, double hi) {
    p.min = std::min(lo, p.value);
    p.max = std::max(hi, p.value);
    if (!(p.max > p.min)) p.max = p.min + 1;
    // About 200 steps of travel, rounded to 1, 2 or 5 times a power of ten.
    const double raw = (p.max - p.min) / 200;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    p.step = raw / mag < 2 ? mag : raw / mag < 5 ? 2 * mag : 5 * mag;
    // Ends on whole steps, so that the slider's positions are round numbers (0.865, not 0.864215).
    p.min = std::floor(p.min / p.step + 1e-9) * p.step;
    p.max = std::ceil(p.max / p.step - 1e-9) * p.step;
    if (p.length > 0) out_.push_back(std::move(p));
  }

  double max_force_N_;
  std::map<std::pair<int, int>, int> number_length_;
  std::map<std::string, int> seen_;
  std::vector<Parameter> out_;
};

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

void opt(Collector& c, const std::string& prefix, const char* what, const std::optional<Quantity>& q,
         const SiRange* range = nullptr) {
  if (q) c.quantity(prefix + "." + what, prefix + " " + what, "physical", *q, range);
}

}  // namespace

std::vector<Parameter> material_parameters(const std::string& text, const calibration::CalibrationSet& calibration,
                                           double max_force_N) {
  auto file = std::make_shared<const SourceFile>("<parameters>", text);
  Diagnostics diags;
  const auto tokens = lex(file, diags);
  const auto syntax = parse(tokens, file, diags);
  Collector c(tokens, max_force_N);
  const auto& map = calibration.roughness_map();
  // The calibrated stimuli's roughness: the map's measured force range through the ratio scale.
  const double r_lo = map.force ? map.percept_of(map.force->min) : 0.0;
  const double r_hi = map.force ? map.percept_of(map.force->max) : 2.0;
  const SiRange period{0.3e-3, 20e-3};
  const SiRange size{5e-3, 228.6e-3};  // up to the thesis joystick's 9 inch workspace (Table 2)
  const SiRange smoothing{0, 2e-3};
  for (const auto& st : syntax.statements) {
    std::visit(Overloaded{
                   [&](const RoughnessStmt& s) {
                     if (s.value) c.plain("roughness", "roughness", "perceptual", s.value_location, *s.value, r_lo, r_hi);
                   },
                   [&](const PerceptStmt& s) {
                     if (s.value) c.plain(s.word, s.word, "perceptual", s.value_location, *s.value, 0, 1);
                   },
                   [&](const GratingStmt& s) {
                     opt(c, "grating", "period", s.period, &period);
                     opt(c, "grating", "hill", s.hill);
                     opt(c, "grating", "amplitude", s.amplitude);
                     opt(c, "grating", "orientation", s.orientation);
                     opt(c, "grating", "smoothing", s.smoothing, &smoothing);
                   },
                   [&](const HeightmapStmt& s) {
                     c.quantity("heightmap.width", "image width", "physical", s.width, &size);
                     opt(c, "heightmap", "height", s.height, &size);
                     opt(c, "heightmap", "smoothing", s.smoothing, &smoothing);
                     opt(c, "heightmap", "amplitude", s.amplitude);
                     opt(c, "heightmap", "sampling", s.sampling, &smoothing);
                     opt(c, "heightmap", "depth", s.depth, &smoothing);
                     opt(c, "heightmap", "press", s.press);
                   },
                   [&](const PatternStmt& s) {
                     const std::string p = "pattern";
                     opt(c, p, "valley", s.valley, &period);
                     opt(c, p, "hill", s.hill, &period);
                     opt(c, p, "offset", s.offset, &period);
                     opt(c, p, "feature", s.feature, &period);
                     opt(c, p, "pixel", s.pixel, &smoothing);
                     opt(c, p, "amplitude", s.amplitude);
                     if (s.kernel) c.plain("pattern.kernel", "pattern kernel (px)", "physical", s.kernel->location, s.kernel->value, 0, 16);
                   },
                   [&](const SpringStmt& s) { c.quantity("spring.stiffness", "spring stiffness", "physical", s.stiffness); },
                   [&](const DamperStmt& s) { c.quantity("damper.damping", "damping", "physical", s.damping); },
                   [&](const SizeStmt& s) {
                     c.quantity("size.width", "patch width", "physical", s.width, &size);
                     opt(c, "size", "height", s.height, &size);
                   },
                   [&](const LawStmt& s) {
                     const std::string prefix = std::string(s.physics ? "physics." : "force.") + s.name;
                     for (const auto& a : s.args) {
                       if (!a.quantity) continue;
                       if (a.quantity->unit.empty())
                         c.plain(prefix + "." + a.name, s.name + " " + a.name, "physical", a.quantity->location,
                                 a.quantity->value, 0, std::max(10.0, 2 * a.quantity->value));
                       else
                         c.quantity(prefix + "." + a.name, s.name + " " + a.name, "physical", *a.quantity);
                     }
                   },
                   [&](const EnergyStmt& s) {
                     c.quantity("energy.budget", "energy budget", "physical", s.budget);
                     opt(c, "energy", "refill", s.refill);
                   },
                   [](const auto&) {},
               },
               st.node);
  }
  return c.take();
}

std::vector<Parameter> workspace_parameters(const std::string& text) {
  auto file = std::make_shared<const SourceFile>("<parameters>", text);
  Diagnostics diags;
  const auto tokens = lex(file, diags, LexOptions{.commas = true});
  const auto ws = parse_workspace(tokens, file, diags);
  Collector c(tokens, 10);
  const SiRange size{1e-3, 500e-3};
  const SiRange position{-250e-3, 250e-3};
  if (ws.width) c.quantity("workspace.width", "workspace width", "physical", *ws.width, &size);
  if (ws.height) c.quantity("workspace.height", "workspace height", "physical", *ws.height, &size);
  for (std::size_t i = 0; i < ws.patches.size(); ++i) {
    const auto& p = ws.patches[i];
    const std::string n = "patch." + std::to_string(i);
    // "patch 2 (corduroy) x": the index keeps two patches of one material apart.
    const std::string what = p.material.size() > 24 ? p.material.substr(0, 21) + "..." : p.material;
    const std::string label = "patch " + std::to_string(i) + " (" + what + ")";
    c.quantity(n + ".x", label + " x", "physical", p.x, &position);
    c.quantity(n + ".y", label + " y", "physical", p.y, &position);
    if (p.width) c.quantity(n + ".width", label + " width", "physical", *p.width, &size);
    if (p.height) c.quantity(n + ".height", label + " height", "physical", *p.height, &size);
  }
  return c.take();
}

std::string format_parameter_value(double value) {
  if (value == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  std::string s = buf;
  // Keep decimal notation: a slider never needs an exponent, and "1e-05" reads badly in a material.
  if (s.find('e') != std::string::npos) {
    std::snprintf(buf, sizeof buf, "%.9f", value);
    s = buf;
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  return s;
}

namespace {

std::size_t offset_of(const SourceFile& f, int line, int column) {
  if (line < 1 || static_cast<std::size_t>(line) > f.line_starts.size())
    throw ParameterError("position out of the text");
  return f.line_starts[static_cast<std::size_t>(line - 1)] + static_cast<std::size_t>(column - 1);
}

}  // namespace

std::string set_parameter(const std::string& text, const std::vector<Parameter>& params, const std::string& name,
                          double value, const std::string& unit) {
  const auto it = std::find_if(params.begin(), params.end(), [&](const Parameter& p) { return p.name == name; });
  if (it == params.end()) {
    std::string known;
    for (const auto& p : params) known += (known.empty() ? "" : ", ") + p.name;
    throw ParameterError("no parameter '" + name + "' in this text; it has: " + (known.empty() ? "none" : known));
  }
  if (!std::isfinite(value)) throw ParameterError("the value of '" + name + "' must be a finite number");
  double written = value;
  if (!unit.empty() && unit != it->unit) {
    const auto from = schema::find_unit(unit);
    const auto to = schema::find_unit(it->unit);
    if (!from) throw ParameterError("unknown unit '" + unit + "'");
    if (!to) throw ParameterError("'" + name + "' is a plain number; give it without a unit");
    if (from->dimension != to->dimension)
      throw ParameterError("'" + unit + "' is a " + std::string(schema::dimension_name(from->dimension)) + " unit, but '" +
                           name + "' is a " + std::string(schema::dimension_name(to->dimension)) + " (written in " +
                           it->unit + ")");
    written = value * from->to_si / to->to_si;
  }
  const SourceFile f("<parameters>", text);
  const std::size_t at = offset_of(f, it->line, it->column);
  if (at + static_cast<std::size_t>(it->length) > text.size()) throw ParameterError("parameter list is out of date");
  std::string out = text;
  out.replace(at, static_cast<std::size_t>(it->length), format_parameter_value(written));
  return out;
}

std::string place_workspace_patch(const std::string& text, int index, double x_mm, double y_mm, double width_mm,
                                  double height_mm) {
  if (!std::isfinite(x_mm) || !std::isfinite(y_mm)) throw ParameterError("a patch's centre must be finite (mm)");
  if (!(width_mm > 0) || !(height_mm > 0) || !std::isfinite(width_mm) || !std::isfinite(height_mm))
    throw ParameterError("a patch's size must be positive and finite (mm)");
  auto file = std::make_shared<const SourceFile>("<workspace>", text);
  Diagnostics diags;
  const auto tokens = lex(file, diags, LexOptions{.commas = true});
  const auto ws = parse_workspace(tokens, file, diags);
  if (index < 0 || static_cast<std::size_t>(index) >= ws.patches.size())
    throw ParameterError("no patch " + std::to_string(index) + "; the workspace has " +
                         std::to_string(ws.patches.size()));
  const auto& p = ws.patches[static_cast<std::size_t>(index)];
  // Edits from the end of the line backwards, so earlier offsets stay valid.
  struct Edit {
    std::size_t at, length;
    std::string with;
  };
  std::vector<Edit> edits;
  const auto mm_of = [](const Quantity& q, double mm) {
    const auto u = schema::find_unit(q.unit);
    return format_parameter_value(u ? mm * 1e-3 / u->to_si : mm);
  };
  const auto number_len = [&](const Quantity& q) {
    for (const auto& t : tokens)
      if (t.kind == TokenKind::Number && t.location.line == q.location.line && t.location.column == q.location.column)
        return static_cast<std::size_t>(t.location.length);
    throw ParameterError("cannot find the number of " + q.text());
  };
  const auto replace = [&](const Quantity& q, double mm) {
    edits.push_back({offset_of(*file, q.location.line, q.location.column), number_len(q), mm_of(q, mm)});
  };
  const auto end_of = [&](const Quantity& q) {
    return offset_of(*file, q.location.line, q.location.column) + static_cast<std::size_t>(q.location.length);
  };
  replace(p.x, x_mm);
  replace(p.y, y_mm);
  if (p.width) {
    replace(*p.width, width_mm);
    if (p.height)
      replace(*p.height, height_mm);
    else if (std::abs(width_mm - height_mm) > 1e-9)
      edits.push_back({end_of(*p.width), 0, " x " + format_parameter_value(height_mm) + " mm"});
  } else {
    edits.push_back({end_of(p.y), 0,
                     " size " + format_parameter_value(width_mm) + " mm x " + format_parameter_value(height_mm) + " mm"});
  }
  std::sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) { return a.at > b.at; });
  std::string out = text;
  for (const auto& e : edits) out.replace(e.at, e.length, e.with);
  return out;
}

}  // namespace sandpaper::compiler
