// The physical layer: gratings, force laws, patterns and quantization, each checked against its range.
#include "resolver_impl.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "sandpaper/schema/confined_path.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/compiler/height_field_image.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/schema/force_laws.hpp"
#include "sandpaper/compiler/patterns.hpp"
#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/compiler/thesis_stimuli.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::compiler::resolve_detail {

void Resolver::physical(const Statement& st, ResolvedMaterial& m) {
  // What the file states physically beats a perceptual target it inherits for the same parameter.
  if (std::holds_alternative<SpringStmt>(st.node)) drop_targets(m, "spring.stiffness");
  else if (std::holds_alternative<DamperStmt>(st.node)) drop_targets(m, "damper.damping");
  else if (std::holds_alternative<GratingStmt>(st.node) || std::holds_alternative<HeightmapStmt>(st.node) ||
           std::holds_alternative<PatternStmt>(st.node))
    drop_targets(m, "texture.period");
  if (const auto* g = std::get_if<GratingStmt>(&st.node)) grating(*g, st, m);
  else if (const auto* l = std::get_if<LawStmt>(&st.node)) law(*l, st, m);
  else if (const auto* e = std::get_if<EnergyStmt>(&st.node)) {
    if (non_negative(e->budget, "energy budget", "")) m.energy_budget = stated_param(e->budget, Layer::Physical);
    if (e->refill && non_negative(*e->refill, "refill power", "")) m.energy_refill = stated_param(*e->refill, Layer::Physical);
  }
  else if (const auto* h = std::get_if<HeightmapStmt>(&st.node)) heightmap(*h, m);
  else if (const auto* s = std::get_if<SpringStmt>(&st.node)) {
    if (non_negative(s->stiffness, "spring stiffness", "a negative spring pushes the hand away: write `force Bump stiffness ...`"))
      m.spring = stated_param(s->stiffness, Layer::Physical);
  } else if (const auto* d = std::get_if<DamperStmt>(&st.node)) {
    if (non_negative(d->damping, "damping", "negative damping injects energy: write `force AntiViscous damping ...` (its energy is bounded)"))
      m.damper = stated_param(d->damping, Layer::Physical);
  } else if (const auto* pt = std::get_if<PatternStmt>(&st.node)) {
    pattern(*pt, st, m);
  } else if (const auto* q = std::get_if<QuantizeStmt>(&st.node)) {
    quantize(*q, m);
  } else if (const auto* z = std::get_if<SizeStmt>(&st.node)) {
    if (!positive(z->width, "patch width")) return;
    m.size_width = stated_param(z->width, Layer::Physical);
    m.size_height = m.size_width;
    if (z->height) {
      if (!positive(*z->height, "patch height")) return;
      m.size_height = stated_param(*z->height, Layer::Physical);
    }
  }
}

void Resolver::grating(const GratingStmt& g, const Statement& st, ResolvedMaterial& m) {
  const auto* base = std::get_if<ResolvedGrating>(&m.texture);
  if (!g.period && !base) {
    diags_.error("E0315", g.location, "this grating has no period, and the file inherits no grating to take it from",
                 "give it one: grating period 2.5 mm" + std::string(g.hill ? " " + g.hill->text() : std::string()) +
                     ", or start from a grating with `like corduroy`");
    return;
  }
  bool ok = !g.period || positive(*g.period, "grating period");
  if (g.hill && !(g.hill->si > 0 && g.hill->si < 1)) {
    diags_.error("E0304", g.hill->location, "hill " + g.hill->text() + " is outside 0-100 %",
                 "the hill is the fraction of each period that is raised: use a value between 0% and 100%, e.g. 50%");
    ok = false;
  }
  if (g.smoothing) ok = non_negative(*g.smoothing, "smoothing", "") && ok;
  if (g.amplitude) ok = non_negative(*g.amplitude, "force amplitude", "") && ok;
  if (!ok) return;
  // What this statement leaves out it inherits from an inherited grating, else the defaults.
  ResolvedGrating r;
  r.period = g.period ? stated_param(*g.period, Layer::Physical) : base->period;
  r.hill = g.hill ? stated_param(*g.hill, Layer::Physical)
                  : base ? base->hill : default_param(0.5, "50% (thesis 3.5.2: hill 128 px, valley 128 px)");
  r.orientation = g.orientation ? stated_param(*g.orientation, Layer::Physical)
                                : base ? base->orientation : default_param(0.0, "0 deg (ribs across x)");
  if (g.smoothing) r.smoothing = stated_param(*g.smoothing, Layer::Physical);
  else if (base) r.smoothing = base->smoothing;
  r.location = st.location;
  m.texture = r;
  if (g.amplitude) m.max_lateral_force = stated_param(*g.amplitude, Layer::Physical);
}

void Resolver::law(const LawStmt& l, const Statement& st, ResolvedMaterial& m) {
  const auto family = l.physics ? schema::LawFamily::Physics : schema::LawFamily::Force;
  const schema::LawDef* def = schema::find_law(family, l.name);
  if (!def) throw InternalError("resolver: law '" + l.name + "' passed the parser but is not in the table");
  ResolvedLaw r;
  r.physics = l.physics;
  r.name = l.name;
  r.text = st.text;
  r.location = l.name_location;
  bool ok = true;
  for (const auto& p : def->params) {
    const LawArg* arg = nullptr;
    for (const auto& a : l.args)
      if (a.name == p.name) arg = &a;
    if (!arg) {
      if (p.required) {
        diags_.error("E0311", l.name_location,
                     std::string(schema::family_keyword(family)) + " " + l.name + " needs its " + std::string(p.name),
                     "add " + std::string(p.name) + " <value>, e.g. `" + std::string(schema::family_keyword(family)) +
                         " " + l.name + " " + example_args(*def) + "`");
        ok = false;
        continue;
      }
      if (p.kind == schema::LawParamKind::Axes) continue;
      r.params.emplace_back(std::string(p.name), default_param(p.default_si, std::string(p.default_text)));
      continue;
    }
    if (p.kind == schema::LawParamKind::Axes) {
      r.axes = arg->word == "x" ? 1 : arg->word == "y" ? 2 : 3;
      continue;
    }
    const Quantity& q = *arg->quantity;
    const std::string what = l.name + " " + std::string(p.name);
    if (!p.any_sign) {
      const bool zero_ok = (!p.required && p.default_si == 0) || p.kind == schema::LawParamKind::Number;
      if (zero_ok ? !non_negative(q, what.c_str(), "") : !positive(q, what.c_str())) {
        ok = false;
        continue;
      }
    }
    Param v = stated_param(q, Layer::Physical);
    if (q.unit.empty()) v.stated = fmt_num(q.value);
    r.params.emplace_back(std::string(p.name), v);
  }
  if (ok) m.laws.push_back(std::move(r));
}

std::string Resolver::example_args(const schema::LawDef& def) {
  std::string out;
  for (const auto& p : def.params) {
    if (!p.required) continue;
    if (!out.empty()) out += ' ';
    out += std::string(p.name) + " ";
    switch (p.dimension) {
      case schema::Dimension::Stiffness: out += "200 N/m"; break;
      case schema::Dimension::Damping: out += "2 N*s/m"; break;
      case schema::Dimension::Force: out += "0.5 N"; break;
      case schema::Dimension::Length: out += "5 mm"; break;
      case schema::Dimension::Mass: out += "50 g"; break;
      case schema::Dimension::Time: out += "20 ms"; break;
      default: out += "1"; break;
    }
  }
  return out;
}

void Resolver::inherit_pattern(ResolvedPattern& p, const std::string& label) {
  inherit(p.pixel, label);
  for (auto* o : {&p.valley, &p.hill, &p.offset, &p.feature, &p.kernel, &p.refilter, &p.seed, &p.count}) inherit(*o, label);
}

std::optional<Param> Resolver::whole_pixels(const Quantity& q, double pixel_m, int min_px, const char* what) {
  double px = std::round(q.si / pixel_m);
  if (!(q.si >= 0) || px < min_px || px > kMaxPatternPixels) {
    diags_.error("E0304", q.location,
                 std::string(what) + " " + q.text() + " is " + fmt_num(q.si / pixel_m) + " pixels of " +
                     fmt_num(pixel_m * 1e3) + " mm",
                 "give " + std::string(what) + " of " + (min_px > 0 ? "at least one pixel" : "zero or more pixels") +
                     " and at most " + std::to_string(kMaxPatternPixels) + " pixels");
    return std::nullopt;
  }
  Param p = stated_param(q, Layer::Physical);
  p.si = px * pixel_m;
  if (std::abs(q.si / pixel_m - px) > 1e-6) p.stated += " (rounded to " + fmt_num(px) + " px)";
  return p;
}

std::optional<Param> Resolver::plain(const PlainNumber& n, double lo, double hi, bool integer, const char* what,
                           const std::string& stated_prefix) {
  bool whole = std::floor(n.value) == n.value;
  if (n.value < lo || n.value > hi || (integer && !whole)) {
    diags_.error("E0304", n.location, std::string(what) + " " + n.text + " is out of range",
                 std::string("give ") + (integer ? "a whole number" : "a number") + " from " + fmt_num(lo) + " to " +
                     fmt_num(hi));
    return std::nullopt;
  }
  return Param{n.value, stated_prefix + " " + n.text, Layer::Physical, n.location.str(), n.location};
}

void Resolver::pattern(const PatternStmt& p, const Statement& st, ResolvedMaterial& m) {
  ResolvedPattern r;
  if (p.kind == "bars") r.kind = PatternKind::Bars;
  else if (p.kind == "grid") r.kind = PatternKind::Grid;
  else if (p.kind == "perlin") r.kind = PatternKind::Perlin;
  else if (p.kind == "noise") r.kind = PatternKind::Noise;
  else r.kind = PatternKind::Stripes;
  r.location = st.location;
  if (p.pixel) {
    if (!positive(*p.pixel, "pixel pitch")) return;
    r.pixel = stated_param(*p.pixel, Layer::Physical);
  } else {
    r.pixel = default_param(kThesisPixel_m, "0.37 mm (thesis 3.5.1 and Appendix A: 1 pixel = .37 mm)");
  }
  const double px = r.pixel.si;
  bool ok = true;
  auto length = [&](const std::optional<Quantity>& q, std::optional<Param>& slot, int min_px, const char* what) {
    if (!q) return;
    slot = whole_pixels(*q, px, min_px, what);
    ok = ok && slot.has_value();
  };
  length(p.valley, r.valley, 1, "the valley width");
  length(p.hill, r.hill, 1, "the hill width");
  length(p.offset, r.offset, 0, "the row offset");
  length(p.feature, r.feature, 1, "the feature size");
  auto number = [&](const std::optional<PlainNumber>& n, std::optional<Param>& slot, double lo, double hi, bool integer,
                    const char* what, const char* prefix) {
    if (!n) return;
    slot = plain(*n, lo, hi, integer, what, prefix);
    ok = ok && slot.has_value();
  };
  number(p.kernel, r.kernel, 0, kMaxPatternKernel, false, "the kernel size", "kernel");
  number(p.refilter, r.refilter, 0, kMaxPatternKernel, false, "the second pass's kernel size", "refilter");
  number(p.seed, r.seed, 0, 9007199254740991.0, true, "the seed", "seed");  // 2^53 - 1: exact in a double
  number(p.count, r.count, 1, 64, true, "the stripe count", "count");
  if (p.amplitude) ok = non_negative(*p.amplitude, "force amplitude", "") && ok;
  if (!ok) return;
  if (r.kind == PatternKind::Noise && !r.feature)
    r.feature = default_param(px, "one pixel (thesis 4.3: Noise alternates high forces closely)");
  if ((r.kind == PatternKind::Perlin || r.kind == PatternKind::Noise) && !r.seed)
    r.seed = default_param(1, "1 (thesis 4.3: the Perlins share one seed pattern)");
  m.texture = r;
  if (p.amplitude) m.max_lateral_force = stated_param(*p.amplitude, Layer::Physical);
}

void Resolver::quantize(const QuantizeStmt& q, ResolvedMaterial& m) {
  if (auto bits = plain(q.bits, 1, 16, true, "the number of bits", "quantize")) {
    bits->stated += " bit";
    m.quantize_bits = bits;
  }
}

}  // namespace sandpaper::compiler::resolve_detail
