// The perceptual layer: roughness and the other perceptual words through their maps, and the
// warnings where a map extrapolates.
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

namespace {

bool outside(const calibration::Range& r, double x) { return x < r.min * (1 - 1e-9) || x > r.max * (1 + 1e-9); }

}  // namespace

// A value the map's (widened) domain admits but its fit never saw: it compiles, and says so.
void Resolver::warn_beyond_stimuli(const calibration::PsychophysicalMap& map, const SourceLocation& at,
                                   const std::string& stated, double si, const char* si_unit) {
  const auto shown = [&](double v) { return schema::display_value(v, si_unit); };
  diags_.warning("W0322", at,
                 stated + " (" + shown(si) + ") is outside the stimuli the " + map.id + " map was fitted on (" +
                     shown(map.stimulus_range->min) + " to " + shown(map.stimulus_range->max) +
                     "); its domain was widened to keep the named levels compiling, and the map extrapolates here",
                 "the prediction is less certain here; a design with stimuli out to this value measures it");
}

void Resolver::roughness(const RoughnessStmt& r, ResolvedMaterial& m) {
  const auto& map = ctx_.calibration.roughness_map();
  double value = 0;
  std::string stated;
  if (r.value) {
    value = *r.value;
    stated = "roughness " + fmt_num(value);
    if (value < 0) {
      diags_.error("E0304", r.value_location, "roughness " + fmt_num(value) + " is negative",
                   "roughness runs from 0 (no lateral force) to 1 (" + fmt_num(map.reference_si) + " N, the strongest calibrated stimulus)");
      return;
    }
  } else {
    const auto* lv = ctx_.calibration.find_level(r.level);
    if (!lv) {
      std::vector<std::string> names;
      for (const auto& l : ctx_.calibration.roughness_levels()) names.push_back(l.name);
      std::string guess = closest_match(r.level, names);
      std::string all;
      for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
      diags_.error("E0307", r.value_location, "unknown roughness level '" + r.level + "'",
                   guess.empty() ? "levels are: " + all + " (or give a number, e.g. roughness 0.6)"
                                 : "did you mean `" + guess + "`?");
      return;
    }
    value = lv->value;
    stated = "roughness " + r.level + " (= " + fmt_num(value) + ")";
  }
  if (value > 1.0 && !m.extrapolate) {
    diags_.error("E0303", r.value_location,
                 "roughness " + fmt_num(value) + " is above 1, the strongest calibrated stimulus (" + fmt_num(map.reference_si) + " N = " + fmt_num(map.reference_si / 9.80665e-3) + " gf)",
                 "use a value up to 1, or add the statement `extrapolate` to go beyond the measured range");
    return;
  }
  double force = map.value_for(value);
  m.roughness = Param{value, stated, Layer::Perceptual, r.value_location.str(), r.value_location};
  m.max_lateral_force = Param{force, stated, Layer::Perceptual,
                              r.value_location.str() + " via " + map.provenance(), r.value_location};
  if (value > 1.0)
    diags_.warning("W0303", r.value_location,
                   "roughness " + fmt_num(value) + " extrapolates the " + map.id + " map beyond its strongest stimulus (" + fmt_num(map.reference_si) + " N)");
  else if (value > 0 && map.stimulus_range && outside(*map.stimulus_range, force) && !(map.force && force < map.force->min * (1 - 1e-9)))
    warn_beyond_stimuli(map, r.value_location, stated, force, "N");
  else if (value > 0 && map.force && force < map.force->min * (1 - 1e-9))
    diags_.warning("W0301", r.value_location,
                   "roughness " + fmt_num(value) + " is below the weakest calibrated stimulus (roughness " +
                       fmt_num(map.percept_of(map.force->min)) + ", " + fmt_num(map.force->min) + " N = " + fmt_num(map.force->min / 9.80665e-3) + " gf); the " + map.id + " map extrapolates",
                   "the prediction is less certain here");
}

void Resolver::percept(const PerceptStmt& s, const Statement& st, ResolvedMaterial& m) {
  const PerceptWord* w = find_percept_word(s.word);
  if (!w) throw InternalError("resolver: perceptual word '" + s.word + "' passed the parser but is not in the table");
  const calibration::PsychophysicalMap* map = ctx_.calibration.compile_map(w->percept);
  if (!map) {
    diags_.error("E0320", st.location,
                 "no map to compile `" + s.word + "` through: the calibration has no map with percept = \"" +
                     w->percept + "\" and use = \"compile\"",
                 std::string("add one to calibration/maps/ (docs/CALIBRATION.md), or give it physically: ") + w->physical);
    return;
  }
  double value = 0;
  std::string stated;
  if (s.value) {
    value = *s.value;
    stated = s.word + " " + fmt_num(value);
  } else {
    const calibration::Level* level = nullptr;
    std::vector<std::string> names;
    for (const auto* l : ctx_.calibration.levels(w->percept)) {
      names.push_back(l->name);
      if (l->name == s.level) level = l;
    }
    if (!level) {
      std::string guess = closest_match(s.level, names), all;
      for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
      const std::string number = "give a number, e.g. " + s.word + " 0.5";
      diags_.error("E0307", s.value_location, "unknown " + s.word + " level '" + s.level + "'",
                   !guess.empty()  ? "did you mean `" + guess + "`?"
                   : names.empty() ? s.word + " has no named levels (calibration/levels/ has none for " + w->percept +
                                         "): " + number
                                   : "levels are: " + all + " (or " + number + ")");
      return;
    }
    value = level->value;
    stated = s.word + " " + s.level + " (= " + fmt_num(value) + ")";
  }
  const auto shown = [&](double si) { return schema::display_value(si, w->si_unit); };
  double top = 1, bottom = 0;
  if (const auto domain = ratio_domain(*map)) {
    const double a = map->percept_of(domain->min), b = map->percept_of(domain->max);
    top = std::max(a, b);
    bottom = std::min(a, b);
  }
  const std::string scale = "1 is " + shown(map->reference_si) + " on the " + map->id + " map";
  if (value < 0 || (value == 0 && w->zero_refused)) {
    diags_.error("E0304", s.value_location,
                 s.word + " " + fmt_num(value) + (value < 0 ? " is negative" : std::string(" ") + w->zero_refused),
                 "give a " + s.word + " above 0 (" + scale + "), or give it physically: " + w->physical);
    return;
  }
  if (value > top * (1 + 1e-9) && !m.extrapolate) {
    diags_.error("E0303", s.value_location,
                 s.word + " " + fmt_num(value) + " is above " + fmt_num(top) + ", the top of the " + map->id +
                     " map's domain (" + shown(map->value_for(top)) + ")",
                 "use a value up to " + fmt_num(top) + ", or add the statement `extrapolate` to go beyond the map's domain");
    return;
  }
  Param p{map->value_for(value), stated, Layer::Perceptual, s.value_location.str() + " via " + map->provenance(),
          s.value_location};
  if (value > top * (1 + 1e-9))
    diags_.warning("W0303", s.value_location,
                   s.word + " " + fmt_num(value) + " (" + shown(p.si) + ") extrapolates the " + map->id +
                       " map beyond the top of its domain (" + shown(map->value_for(top)) + ")");
  else if (value > 0 && value >= bottom * (1 - 1e-9) && map->stimulus_range && outside(*map->stimulus_range, p.si))
    warn_beyond_stimuli(*map, s.value_location, stated, p.si, w->si_unit);
  else if (value > 0 && value < bottom * (1 - 1e-9))
    diags_.warning("W0301", s.value_location,
                   s.word + " " + fmt_num(value) + " (" + shown(p.si) + ") is below the bottom of the " + map->id +
                       " map's domain (" + s.word + " " + fmt_num(bottom) + ", " + shown(map->value_for(bottom)) +
                       "); the map extrapolates",
                   "the prediction is less certain here");
  const std::string param = w->parameter;
  drop_targets(m, param);
  if (param == "damper.damping") m.damper = p;
  else if (param == "friction.coefficient") m.friction_coefficient = p;
  else if (param == "spring.stiffness") m.spring = p;
  else if (param == "texture.period") {
    // The period of the grating this file inherits (its other parameters kept), or a new grating.
    ResolvedGrating g;
    if (const auto* base = std::get_if<ResolvedGrating>(&m.texture)) g = *base;
    else {
      g.hill = default_param(0.5, "50% (thesis 3.5.2: hill 128 px, valley 128 px)");
      g.orientation = default_param(0.0, "0 deg (ribs across x)");
    }
    g.period = p;
    g.location = st.location;
    m.texture = g;
  } else throw InternalError("resolver: no parameter '" + param + "' for perceptual word '" + s.word + "'");
  m.percepts.push_back({s.word, w->percept, param,
                        Param{value, stated, Layer::Perceptual, s.value_location.str(), s.value_location}, map->id,
                        map->file, map->provisional, map->real_material()});
}

void Resolver::drop_targets(ResolvedMaterial& m, const std::string& parameter) {
  std::erase_if(m.percepts, [&](const PerceptTarget& t) { return t.parameter == parameter; });
}

}  // namespace sandpaper::compiler::resolve_detail

namespace sandpaper::compiler {

using resolve_detail::fmt_num;

// The roughness map's domain: warn where a roughness target extrapolates it. Called once the
// texture has compiled, so an image that cannot be read reports only its E0401.
void warn_roughness_domain(const ResolvedMaterial& m, const calibration::CalibrationSet& cal, Diagnostics& diags) {
  const auto& map = cal.roughness_map();
  if (m.roughness && m.roughness->layer == Layer::Perceptual) {
    if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) {
      double p = g->period.si;
      if (map.period && !map.period->contains(p))
        diags.warning("W0302", m.roughness->location,
                       "grating period " + fmt_num(p * 1e3) + " mm is outside the periods the " + map.id +
                           " map was measured on (" + fmt_num(map.period->min * 1e3) + "-" +
                           fmt_num(map.period->max * 1e3) + " mm); the roughness extrapolates",
                       "periods from " + fmt_num(map.period->min * 1e3) + " mm to " + fmt_num(map.period->max * 1e3) +
                           " mm keep the prediction inside the data");
    } else if (std::holds_alternative<ResolvedHeightmap>(m.texture)) {
      diags.warning("W0304", m.roughness->location,
                     "the " + map.id + " map was measured on gratings; for an image texture the roughness extrapolates",
                     "treat the roughness of image textures as approximate");
    } else if (std::holds_alternative<ResolvedPattern>(m.texture)) {
      diags.warning("W0304", m.roughness->location,
                     "the " + map.id + " map was measured on version-2 gratings; for a pattern texture the roughness extrapolates",
                     "treat the roughness of pattern textures as approximate, or give the force with `amplitude`");
    }
  }
}

}  // namespace sandpaper::compiler
