#include "sandpaper/compiler/knowledge_report.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sandpaper/schema/units.hpp"

namespace sandpaper::compiler {
namespace {

using calibration::CalibrationSet;

std::string num(double v, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

double unit_si(const char* name) { return schema::find_unit(name)->to_si; }
std::string in_pu(double newtons) { return num(newtons / unit_si("pu"), 3) + " pu"; }
std::string in_gf(double newtons) { return num(newtons / unit_si("gf"), 3) + " gf"; }
std::string in_ju(double newtons) { return num(newtons / unit_si("ju"), 3) + " ju"; }
std::string mm(double m) { return num(m * 1e3, 4) + " mm"; }
std::string percent(double fraction) { return num(fraction * 100, 3) + " %"; }

const char* period_word(const std::string& kind) { return kind == "perlin" ? "feature size" : "period"; }

// Which thesis non-textural the material is: by stimulus name (its own name or the nearest `like`),
// else by its force terms when it has no texture (force laws; `spring` is Spring, `damper` Viscous;
// no force at all is Nothing).
const calibration::NonTexturalConfidence* match_non_textural(const ResolvedMaterial& m,
                                                            const calibration::BelievabilityData& b) {
  if (const auto* n = b.find_stimulus(m.name)) return n;
  if (!m.like_chain.empty())
    if (const auto* n = b.find_stimulus(m.like_chain.front())) return n;
  if (!std::holds_alternative<std::monostate>(m.texture)) return nullptr;
  std::vector<std::string> laws;
  for (const auto& l : m.laws)
    if (!l.physics && l.name != "Null") laws.push_back(l.name);
  if (m.spring) laws.push_back("Spring");
  if (m.damper) laws.push_back("Viscous");
  // `force Nothing` beside other terms adds nothing.
  if (laws.size() > 1) laws.erase(std::remove(laws.begin(), laws.end(), "Nothing"), laws.end());
  for (const auto& l : m.laws)
    if (l.physics) return nullptr;  // a physics model is none of Ch. 4's stimuli
  if (laws.empty()) return b.find_law("Nothing");
  if (laws.size() != 1) return nullptr;
  return b.find_law(laws.front());
}

GroupPlacement place(const calibration::GroupsData& data, const char* id, double force_N, double period_m) {
  GroupPlacement g;
  g.grouping = data.find(id);
  if (!g.grouping) return g;
  g.hit = g.grouping->classify(force_N, period_m);
  g.in_domain = data.in_domain(force_N, period_m);
  g.nearest = data.nearest(force_N, period_m);
  return g;
}

std::string list(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// "below 69.3 gf", "0.917 mm to 1.73 mm", "from 551 gf", "any".
template <typename Format>
std::string side(double lo, double hi, Format fmt) {
  if (lo <= 0 && std::isinf(hi)) return "any";
  if (lo <= 0) return "below " + fmt(hi);
  if (std::isinf(hi)) return "from " + fmt(lo);
  return fmt(lo) + " to " + fmt(hi);
}

std::string region_range(const calibration::GroupRegion& r) {
  return "force " + side(r.force_min_N, r.force_max_N, in_ju) + ", period " + side(r.period_min_m, r.period_max_m, mm);
}

nlohmann::json region_json(const calibration::GroupRegion& r) {
  auto bound = [](double v) { return std::isinf(v) ? nlohmann::json(nullptr) : nlohmann::json(v); };
  nlohmann::json j{{"force_min_N", r.force_min_N},   {"force_max_N", bound(r.force_max_N)},
                   {"period_min_m", r.period_min_m}, {"period_max_m", bound(r.period_max_m)},
                   {"stimuli", r.stimuli},           {"measured", r.measured()}};
  if (!r.goes_with.empty()) j["goes_with"] = r.goes_with;
  if (!r.sometimes.empty()) j["sometimes"] = r.sometimes;
  if (!r.note.empty()) j["note"] = r.note;
  return j;
}

nlohmann::json placement_json(const GroupPlacement& g, const calibration::GroupsData& data) {
  nlohmann::json j{{"grouping", g.grouping->id},
                   {"group", g.hit.group->id},
                   {"name", g.hit.group->name},
                   {"in_domain", g.in_domain},
                   {"extrapolates", !g.in_domain || !g.hit.region->measured()},
                   {"region", region_json(*g.hit.region)},
                   {"nearest_stimulus", g.nearest ? nlohmann::json(g.nearest->name) : nlohmann::json(nullptr)},
                   {"where", g.grouping->where},
                   {"file", data.file}};
  if (!g.hit.region->goes_with.empty())
    if (const auto* w = g.grouping->find(g.hit.region->goes_with)) j["goes_with_name"] = w->name;
  return j;
}

}  // namespace

TextureGeometry texture_geometry(const ResolvedMaterial& m) {
  TextureGeometry t;
  if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) {
    t.kind = "grating";
    t.period_m = g->period.si;
  } else if (std::holds_alternative<ResolvedHeightmap>(m.texture)) {
    t.kind = "image";
  } else if (const auto* p = std::get_if<ResolvedPattern>(&m.texture)) {
    switch (p->kind) {
      case PatternKind::Bars:
      case PatternKind::Grid:
        t.kind = p->kind == PatternKind::Bars ? "grating" : "grid";
        if (p->valley && p->hill) t.period_m = p->valley->si + p->hill->si;
        break;
      case PatternKind::Perlin:
        t.kind = "perlin";
        if (p->feature) t.period_m = p->feature->si;
        break;
      case PatternKind::Noise: t.kind = "noise"; break;
      case PatternKind::Stripes: t.kind = "stripes"; break;
    }
  }
  return t;
}

std::string jnd_source(const calibration::ForceJndData& jnd) {
  std::string from;
  for (const auto& j : jnd.jnds)
    if (j.relative && jnd.weber_fraction >= j.fraction_min && jnd.weber_fraction <= j.fraction_max)
      from = j.id + ": " + num(j.fraction_min * 100) + "-" + num(j.fraction_max * 100) + " % of reference force, " + j.citation;
  return num(jnd.weber_fraction * 100) + " % of force (" + (from.empty() ? jnd.weber_rationale : from) + "; " + jnd.file + ")";
}

KnowledgeReport assess_knowledge(const ResolvedMaterial& m, const schema::PatchProgram& p, const CalibrationSet& cal) {
  const auto& k = cal.knowledge();
  KnowledgeReport r;
  r.texture = texture_geometry(m);
  r.force_N = p.max_lateral_force_N;
  if (r.force_N > 0 && r.texture.has_period()) {
    r.region = k.believability.region_for(r.texture.kind);
    if (r.region) r.believable = !r.region->contains(r.force_N, r.texture.period_m);
    r.period_class = place(k.roughness_groups, "period-class", r.force_N, r.texture.period_m);
    if (!r.period_class->grouping) r.period_class.reset();
    if (r.texture.kind == k.roughness_groups.texture) {
      r.character = place(k.roughness_groups, "character", r.force_N, r.texture.period_m);
      if (!r.character->grouping) r.character.reset();
    }
  }
  r.non_textural = match_non_textural(m, k.believability);

  if (r.force_N > 0) {
    const auto& map = cal.roughness_map();
    const auto& jnd = k.force_jnd;
    std::vector<LevelNeighbour> levels;
    for (const auto& l : cal.roughness_levels()) levels.push_back({&l, map.value_for(l.value), 0});
    std::sort(levels.begin(), levels.end(), [](const auto& a, const auto& b) { return a.force_N < b.force_N; });
    for (auto& l : levels) l.jnd_steps = jnd.steps_between(r.force_N, l.force_N);
    for (const auto& l : levels) {
      if (std::abs(l.force_N - r.force_N) <= 1e-6 * l.force_N) r.at = l;
      else if (l.force_N < r.force_N) r.below = l;
      else if (!r.above) r.above = l;
    }
  }
  return r;
}

std::string knowledge_text(const KnowledgeReport& k, const CalibrationSet& cal) {
  const auto& know = cal.knowledge();
  const auto& b = know.believability;
  const auto& groups = know.roughness_groups;
  std::ostringstream os;
  const std::string pad = "                  ";
  // Ch. 4 believability.
  if (k.region) {
    const auto& reg = *k.region;
    const std::string bound = std::string(period_word(k.texture.kind)) + (reg.period_inclusive ? " >= " : " > ") +
                              mm(reg.period_bound_m);
    std::string kinds;
    for (std::size_t i = 0; i < reg.textures.size(); ++i)
      kinds += (i == 0 ? "" : i + 1 == reg.textures.size() ? " and " : ", ") + reg.textures[i] + "s";
    os << "  believable      " << (k.believable ? "yes" : "NO") << ": " << k.texture.kind << " of " << num(k.force_N)
       << " N (" << in_pu(k.force_N) << "), " << period_word(k.texture.kind) << " " << mm(k.texture.period_m);
    if (k.believable)
      os << ", lies outside ch. 4's low-confidence region for " << kinds << " (force < " << in_pu(reg.force_below_N)
         << " and " << bound << ")\n";
    else
      os << " lies inside ch. 4's low-confidence region for " << kinds << " (force < " << in_pu(reg.force_below_N) << " and " << bound
         << "):\n"
         << pad << "such stimuli got mean confidence below " << percent(b.high_confidence)
         << " that they feel like a textured surface (" << b.subjects << " subjects, " << b.stimuli << " stimuli, "
         << b.runs << " runs)\n";
    os << pad << "Minsky 1995 " << reg.where << (reg.reading ? "; a reading: " + reg.reading_note : "") << " (" << b.file
       << ")\n";
  } else if (k.force_N > 0 && !k.non_textural) {
    os << "  believable      not assessed: ch. 4 measured gratings, grids and Perlin textures, not "
       << (k.texture.kind.empty() ? "this texture" : k.texture.kind + " textures") << "\n";
  }
  // 6.3.6 and 6.3.7.
  auto placement = [&](const std::string& label, const GroupPlacement& g) {
    const auto& reg = *g.hit.region;
    os << "  " << label << std::string(16 - label.size(), ' ') << g.hit.group->name << " (" << g.grouping->where
       << "): " << region_range(reg);
    if (!reg.goes_with.empty())
      if (const auto* w = g.grouping->find(reg.goes_with)) os << "; at this force it goes with the " << w->name;
    if (!reg.sometimes.empty())
      if (const auto* s = g.grouping->find(reg.sometimes)) os << "; sometimes sorted as " << s->name;
    os << "\n" << pad << (reg.measured() ? "with " + list(reg.stimuli) : "no Table 8 stimulus here: " + reg.note);
    if (g.nearest) os << "; nearest Table 8 stimulus " << g.nearest->name;
    os << "\n";
    if (!g.in_domain)
      os << pad << "outside the forces and periods Table 8 measured (" << in_ju(groups.forces_N.front()) << " to "
         << in_ju(groups.forces_N.back()) << ", " << mm(groups.periods_m.front()) << " to "
         << mm(groups.periods_m.back()) << "): the grouping extrapolates\n";
    if (k.texture.kind != groups.texture)
      os << pad << "measured on " << groups.texture << "s (Table 8); for a " << k.texture.kind << " this extrapolates\n";
  };
  if (k.period_class) placement("period class", *k.period_class);
  if (k.character) placement("group", *k.character);
  else if (k.period_class)
    os << "  group           not assessed: the characteristic groups of 6.3.7 were measured on " << groups.texture
       << "s only\n";
  // Table 4.
  if (k.non_textural)
    os << "  confidence      thesis non-textural " << k.non_textural->name << ": mean " << percent(k.non_textural->mean)
       << " (+/- " << percent(k.non_textural->sd) << ") that it feels like a textured surface (Minsky 1995 "
       << k.non_textural->where << "; " << b.file << ")\n";
  // 5.4.2: JND steps to the named levels.
  if (k.force_N > 0) {
    auto level = [&](const LevelNeighbour& l) {
      return l.level->name + " (" + in_gf(l.force_N) + ")";
    };
    os << "  force JND       ";
    std::string sep;
    if (k.at) os << "at named level " << level(*k.at), sep = "; ";
    if (k.below) os << sep << num(-k.below->jnd_steps, 3) << " JND above " << level(*k.below), sep = ", ";
    if (k.above) os << sep << num(k.above->jnd_steps, 3) << " JND below " << level(*k.above);
    if (!k.below && !k.at) os << " (below the weakest named level)";
    if (!k.above && !k.at) os << " (above the strongest named level)";
    os << "\n" << pad << "one JND = " << jnd_source(know.force_jnd) << "\n";
  }
  return os.str();
}

namespace {
// Maps listed beside the one that compiles: measured maps of the same percept, including the default
// when a device's own map compiles; other devices' maps are not comparisons for this one.
bool shown_beside(const calibration::PsychophysicalMap& m, const calibration::PsychophysicalMap& compile) {
  return &m != &compile && !m.provisional && m.percept == compile.percept && !m.for_device;
}
}  // namespace

std::string maps_text(const CalibrationSet& cal) {
  std::ostringstream os;
  const auto& compile = cal.roughness_map();
  auto line = [&](const calibration::PsychophysicalMap& m) {
    os << "  " << (&m == &compile ? "compile     " : "comparison  ") << m.id << std::string(m.id.size() < 18 ? 18 - m.id.size() : 1, ' ');
    const auto* main = m.predictor(compile.ratio_predictor);
    if (main) {
      os << "slope " << num(main->coefficient, 3) << " on log " << main->name;
      if (main->t) os << " (t " << num(*main->t, 3) << ")";
    }
    for (const auto& pr : m.predictors) {
      if (&pr == main) continue;
      os << "; log " << pr.name << " " << num(pr.coefficient, 2);
      if (pr.t) os << " (t " << num(*pr.t, 2) << (pr.p ? ", p " + num(*pr.p, 2) : "") << ")";
      if (pr.p && *pr.p >= 0.05) os << ": the " << pr.name << " adds nothing";
    }
    if (m.r_squared) os << "; R^2 " << num(*m.r_squared, 3);
    if (m.domain_device != compile.domain_device)
      os << "\n" << std::string(32, ' ') << "against " << (main ? main->quantity : "?") << ": " << m.effector << " on "
         << m.domain_texture << "s, not the " << compile.domain_device << " joystick";
    os << "\n";
  };
  line(compile);
  for (const auto& m : cal.maps())
    if (shown_beside(m, compile)) line(m);
  return os.str();
}

nlohmann::json knowledge_json(const KnowledgeReport& k, const CalibrationSet& cal) {
  const auto& know = cal.knowledge();
  const auto& b = know.believability;
  nlohmann::json j;
  j["texture"] = k.texture.kind.empty() ? nlohmann::json(nullptr) : nlohmann::json(k.texture.kind);
  j["period_m"] = k.texture.has_period() ? nlohmann::json(k.texture.period_m) : nlohmann::json(nullptr);
  j["compiled_max_lateral_force_N"] = k.force_N;
  if (k.region)
    j["believability"] = {{"believable", k.believable},
                          {"region", k.region->id},
                          {"force_below_N", k.region->force_below_N},
                          {"period_bound_m", k.region->period_bound_m},
                          {"period_inclusive", k.region->period_inclusive},
                          {"reading", k.region->reading ? nlohmann::json(k.region->reading_note) : nlohmann::json(nullptr)},
                          {"high_confidence", b.high_confidence},
                          {"where", k.region->where},
                          {"file", b.file}};
  else j["believability"] = nullptr;
  j["period_class"] = k.period_class ? placement_json(*k.period_class, know.roughness_groups) : nlohmann::json(nullptr);
  j["group"] = k.character ? placement_json(*k.character, know.roughness_groups) : nlohmann::json(nullptr);
  if (k.non_textural)
    j["non_textural"] = {{"name", k.non_textural->name},
                         {"mean_confidence", k.non_textural->mean},
                         {"sd", k.non_textural->sd},
                         {"where", k.non_textural->where},
                         {"file", b.file}};
  else j["non_textural"] = nullptr;
  auto level = [](const std::optional<LevelNeighbour>& l) {
    if (!l) return nlohmann::json(nullptr);
    return nlohmann::json{{"name", l->level->name}, {"value", l->level->value}, {"force_N", l->force_N},
                          {"jnd_steps", l->jnd_steps}};
  };
  if (k.force_N > 0)
    j["force_jnd"] = {{"weber_fraction", know.force_jnd.weber_fraction},
                      {"source", jnd_source(know.force_jnd)},
                      {"file", know.force_jnd.file},
                      {"at_level", level(k.at)},
                      {"level_below", level(k.below)},
                      {"level_above", level(k.above)}};
  else j["force_jnd"] = nullptr;
  return j;
}

nlohmann::json maps_json(const CalibrationSet& cal) {
  nlohmann::json arr = nlohmann::json::array();
  const auto& compile = cal.roughness_map();
  // The compile map first, then the comparisons beside it, as in the text.
  std::vector<const calibration::PsychophysicalMap*> shown{&compile};
  for (const auto& m : cal.maps())
    if (shown_beside(m, compile)) shown.push_back(&m);
  for (const auto* mp : shown) {
    const auto& m = *mp;
    nlohmann::json preds = nlohmann::json::array();
    for (const auto& pr : m.predictors) {
      nlohmann::json p{{"name", pr.name}, {"unit", pr.unit}, {"coefficient", pr.coefficient}};
      p["se"] = pr.se ? nlohmann::json(*pr.se) : nlohmann::json(nullptr);
      p["t"] = pr.t ? nlohmann::json(*pr.t) : nlohmann::json(nullptr);
      p["p"] = pr.p ? nlohmann::json(*pr.p) : nlohmann::json(nullptr);
      preds.push_back(p);
    }
    arr.push_back({{"id", m.id},
                   {"use", mp == &compile ? "compile" : "comparison"},
                   {"predictors", preds},
                   {"r_squared", m.r_squared ? nlohmann::json(*m.r_squared) : nlohmann::json(nullptr)},
                   {"texture", m.domain_texture},
                   {"effector", m.effector},
                   {"device", m.domain_device},
                   {"where", m.where},
                   {"file", m.file}});
  }
  return arr;
}

void warn_believability(const ResolvedMaterial& m, const schema::PatchProgram& p, const CalibrationSet& cal,
                        Diagnostics& diags) {
  const TextureGeometry t = texture_geometry(m);
  if (t.kind != "grating" && t.kind != "grid") return;
  if (!(p.max_lateral_force_N > 0) || !t.has_period()) return;
  const auto& b = cal.knowledge().believability;
  const auto* reg = b.region_for(t.kind);
  if (!reg || !reg->contains(p.max_lateral_force_N, t.period_m)) return;
  // Point at the force where this file states it, else at the texture.
  SourceLocation at;
  if (m.max_lateral_force && m.max_lateral_force->location.file) at = m.max_lateral_force->location;
  else if (const auto* g = std::get_if<ResolvedGrating>(&m.texture)) at = g->location;
  else if (const auto* pt = std::get_if<ResolvedPattern>(&m.texture)) at = pt->location;
  const auto& map = cal.roughness_map();
  diags.warning("W0330", at,
                "this " + t.kind + " may not feel like a textured surface: its maximum lateral force " +
                    num(p.max_lateral_force_N) + " N (" + in_pu(p.max_lateral_force_N) + ") is below " +
                    in_pu(reg->force_below_N) + " and its period " + mm(t.period_m) + " is above " +
                    mm(reg->period_bound_m) + ", where Minsky 1995 ch. 4 found low confidence (mean < " +
                    percent(b.high_confidence) + "; " + b.file + ")",
                "raise the force to at least " + in_pu(reg->force_below_N) + " (" + num(reg->force_below_N) +
                    " N, roughness " + num(map.percept_of(reg->force_below_N), 3) + ") or make the period at most " +
                    mm(reg->period_bound_m));
}

}  // namespace sandpaper::compiler
