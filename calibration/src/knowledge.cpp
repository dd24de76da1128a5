// calibration/knowledge/*.toml: force JND, texture believability, roughness groups. Each file is
// validated against its schema first; what a schema cannot say (measured values in order, regions
// that tile the measured grid, stimuli inside the regions that list them) is checked here.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <tuple>

#include "file_reading.hpp"
#include "sandpaper/schema/force_laws.hpp"

namespace sandpaper::calibration {

namespace {
constexpr double kOnBound = 1e-9;  // relative: two ways of writing one force ("120 ju", "30 pu") meet
}  // namespace

bool LowConfidenceRegion::applies_to(const std::string& texture) const {
  return std::find(textures.begin(), textures.end(), texture) != textures.end();
}

bool LowConfidenceRegion::contains(double force_N, double period_m) const {
  const bool weak = force_N < force_below_N * (1 - kOnBound);
  const bool large = period_inclusive ? period_m >= period_bound_m * (1 - kOnBound)
                                      : period_m > period_bound_m * (1 + kOnBound);
  return weak && large;
}

const LowConfidenceRegion* BelievabilityData::region_for(const std::string& texture) const {
  for (const auto& r : low_confidence)
    if (r.applies_to(texture)) return &r;
  return nullptr;
}

const NonTexturalConfidence* BelievabilityData::find_law(const std::string& law) const {
  for (const auto& n : non_textural)
    if (!n.law.empty() && n.law == law) return &n;
  return nullptr;
}

const NonTexturalConfidence* BelievabilityData::find_stimulus(const std::string& name) const {
  for (const auto& n : non_textural)
    if (!n.stimulus.empty() && n.stimulus == name) return &n;
  return nullptr;
}

Grouping::Hit Grouping::classify(double force_N, double period_m) const {
  for (const auto& g : groups)
    for (const auto& r : g.regions)
      if (r.contains(force_N, period_m)) return {&g, &r};
  return {};
}

const Group* Grouping::find(const std::string& group_id) const {
  for (const auto& g : groups)
    if (g.id == group_id) return &g;
  return nullptr;
}

bool GroupsData::in_domain(double force_N, double period_m) const {
  if (forces_N.empty() || periods_m.empty()) return false;
  const auto within = [](double v, double lo, double hi) { return v >= lo * (1 - kOnBound) && v <= hi * (1 + kOnBound); };
  return within(force_N, forces_N.front(), forces_N.back()) && within(period_m, periods_m.front(), periods_m.back());
}

const MeasuredStimulus* GroupsData::nearest(double force_N, double period_m) const {
  const MeasuredStimulus* best = nullptr;
  double best_d = 0;
  if (!(force_N > 0) || !(period_m > 0)) return nullptr;
  for (const auto& s : stimuli) {
    const double a = std::log(force_N / s.force_N), b = std::log(period_m / s.period_m);
    const double d = a * a + b * b;
    if (!best || d < best_d) best = &s, best_d = d;
  }
  return best;
}

const Grouping* GroupsData::find(const std::string& grouping_id) const {
  for (const auto& g : groupings)
    if (g.id == grouping_id) return &g;
  return nullptr;
}

namespace detail {
namespace {

std::string str(const toml::node_view<const toml::node>& v) { return v.value_or(std::string()); }

void read_force_jnd(const Toml& f, ForceJndData& out) {
  const toml::table& c = f.doc;
  out.file = f.shown_as;
  out.weber_fraction = *c["weber_fraction"].value<double>();
  out.weber_rationale = *c["rationale"].value<std::string>();
  for (const auto& node : *c["jnd"].as_array()) {
    const toml::table& j = *node.as_table();
    ForceJnd x;
    x.id = *j["id"].value<std::string>();
    x.relative = *j["kind"].value<std::string>() == "relative";
    if (const auto* fr = j["fraction"].as_array()) {
      x.fraction_min = *fr->get(0)->value<double>();
      x.fraction_max = *fr->get(1)->value<double>();
    }
    if (auto v = j["value"].node()) x.absolute_N = quantity_si(*v);
    if (const auto* r = j["reference_force"].as_array()) {
      x.force_min_N = quantity_si(*r->get(0));
      x.force_max_N = quantity_si(*r->get(1));
    }
    x.effector = *j["effector"].value<std::string>();
    x.citation = *j["citation"].value<std::string>();
    x.where = *j["where"].value<std::string>();
    out.jnds.push_back(std::move(x));
  }
}

void read_believability(const Toml& f, BelievabilityData& out, Problems& problems) {
  const toml::table& c = f.doc;
  out.file = f.shown_as;
  out.subjects = static_cast<int>(*c["experiment"]["subjects"].value<std::int64_t>());
  out.stimuli = static_cast<int>(*c["experiment"]["stimuli"].value<std::int64_t>());
  out.runs = static_cast<int>(*c["experiment"]["runs"].value<std::int64_t>());
  out.high_confidence = quantity_si(*c["experiment"]["high_confidence"].node());
  out.question = str(c["experiment"]["question"]);
  out.device = str(c["experiment"]["device"]);
  out.citation = str(c["source"]["citation"]);
  out.where = str(c["source"]["where"]);
  std::set<std::string> textures_seen;
  for (const auto& node : *c["low_confidence"].as_array()) {
    const toml::table& r = *node.as_table();
    LowConfidenceRegion x;
    x.id = str(r["id"]);
    for (const auto& t : *r["textures"].as_array()) {
      x.textures.push_back(*t.value<std::string>());
      if (!textures_seen.insert(x.textures.back()).second)
        problems.add(f, t, "texture `" + x.textures.back() + "` is in two low-confidence regions",
                     "give each texture kind one region");
    }
    x.reading = str(r["status"]) == "reading";
    x.reading_note = str(r["reading"]);
    if (x.reading && x.reading_note.empty())
      problems.add(f, r, "a region with status = \"reading\" needs `reading`, saying what was read and why", "");
    x.force_below_N = quantity_si(*r["force_below"].node());
    if (r.contains("period_above") && r.contains("period_from"))
      problems.add(f, *r["period_from"].node(), "give `period_above` (strict) or `period_from` (inclusive), not both", "");
    x.period_inclusive = !r.contains("period_above");
    x.period_bound_m = quantity_si(*r[x.period_inclusive ? "period_from" : "period_above"].node());
    x.where = str(r["where"]);
    x.text = str(r["text"]);
    out.low_confidence.push_back(std::move(x));
  }
  std::set<std::string> names;
  for (const auto& node : *c["non_textural"].as_array()) {
    const toml::table& n = *node.as_table();
    NonTexturalConfidence x;
    x.name = str(n["name"]);
    x.law = str(n["law"]);
    x.stimulus = str(n["stimulus"]);
    x.mean = quantity_si(*n["mean"].node());
    x.sd = quantity_si(*n["sd"].node());
    x.where = str(n["where"]);
    if (!names.insert(x.name).second) problems.add(f, *n["name"].node(), "non-textural `" + x.name + "` is listed twice", "");
    if (!x.law.empty() && !x.stimulus.empty())
      problems.add(f, *n["stimulus"].node(), "give `law` or `stimulus`, not both", "");
    if (!x.law.empty() && !schema::find_law(schema::LawFamily::Force, x.law))
      problems.add(f, *n["law"].node(), "`" + x.law + "` is not a force law of schema/LANGUAGE.md",
                   "use a law name such as AntiViscous, Spring, Bump, Viscous, Nothing");
    if (x.mean > 1) problems.add(f, *n["mean"].node(), "a mean confidence above 100 %", "");
    out.non_textural.push_back(std::move(x));
  }
}

// Index of `v` in the ascending `values` (relative tolerance 1e-6); -1 if absent.
int index_of(const std::vector<double>& values, double v) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (std::abs(values[i] - v) <= 1e-6 * values[i]) return static_cast<int>(i);
  return -1;
}

// Lower and upper edge of measured cell range [first, last] of `values`: geometric midpoints to
// the neighbours, 0 below the lowest and infinity above the highest.
std::pair<double, double> edges(const std::vector<double>& values, int first, int last) {
  const double lo = first == 0 ? 0.0 : std::sqrt(values[first - 1] * values[first]);
  const double hi = last + 1 == static_cast<int>(values.size()) ? std::numeric_limits<double>::infinity()
                                                                : std::sqrt(values[last] * values[last + 1]);
  return {lo, hi};
}

std::vector<double> ascending(const Toml& f, const toml::array& a, const char* what, Problems& problems) {
  std::vector<double> out;
  for (const auto& n : a) {
    out.push_back(quantity_si(n));
    if (out.size() > 1 && !(out.back() > out[out.size() - 2]))
      problems.add(f, n, std::string("measured ") + what + " must be ascending, each larger than the one before", "");
  }
  return out;
}

void read_groups(const Toml& f, GroupsData& out, Problems& problems) {
  const toml::table& c = f.doc;
  out.file = f.shown_as;
  out.percept = str(c["percept"]);
  out.texture = str(c["texture"]);
  out.device = str(c["device"]);
  out.citation = str(c["source"]["citation"]);
  out.where = str(c["source"]["where"]);
  const std::size_t problems_before = problems.count();
  out.forces_N = ascending(f, *c["measured"]["forces"].as_array(), "forces", problems);
  out.periods_m = ascending(f, *c["measured"]["periods"].as_array(), "periods", problems);
  if (problems.count() != problems_before) return;

  // Where a measured value is, or a problem at `n` when it is not one of the measured ones.
  auto cell = [&](const toml::node& n, const std::vector<double>& values, const char* what) {
    int i = index_of(values, quantity_si(n));
    if (i < 0)
      problems.add(f, n, "\"" + *n.value<std::string>() + "\" is not one of the measured " + what,
                   std::string("use a value of [measured] ") + what);
    return i;
  };
  std::set<std::string> stimulus_names;
  for (const auto& node : *c["measured"]["stimulus"].as_array()) {
    const toml::table& s = *node.as_table();
    MeasuredStimulus m{str(s["name"]), quantity_si(*s["force"].node()), quantity_si(*s["period"].node())};
    cell(*s["force"].node(), out.forces_N, "forces");
    cell(*s["period"].node(), out.periods_m, "periods");
    if (!stimulus_names.insert(m.name).second) problems.add(f, *s["name"].node(), "stimulus `" + m.name + "` is listed twice", "");
    out.stimuli.push_back(std::move(m));
  }

  std::set<std::string> grouping_ids;
  for (const auto& gnode : *c["grouping"].as_array()) {
    const toml::table& gt = *gnode.as_table();
    Grouping grouping{str(gt["id"]), str(gt["title"]), str(gt["where"]), str(gt["text"]), {}};
    if (!grouping_ids.insert(grouping.id).second)
      problems.add(f, *gt["id"].node(), "grouping `" + grouping.id + "` is defined twice", "");
    // How often each measured cell is covered, and by which region (for the message).
    std::vector<std::vector<int>> covered(out.forces_N.size(), std::vector<int>(out.periods_m.size(), 0));
    std::vector<std::pair<const toml::node*, std::string>> references;  // goes_with / sometimes
    for (const auto& node : *gt["group"].as_array()) {
      const toml::table& grt = *node.as_table();
      Group g{str(grt["id"]), str(grt["name"]), str(grt["description"]), {}};
      if (grouping.find(g.id)) problems.add(f, *grt["id"].node(), "group `" + g.id + "` is defined twice in grouping `" + grouping.id + "`", "");
      for (const auto& rnode : *grt["region"].as_array()) {
        const toml::table& rt = *rnode.as_table();
        const toml::array& fa = *rt["force"].as_array();
        const toml::array& pa = *rt["period"].as_array();
        const int f0 = cell(*fa.get(0), out.forces_N, "forces"), f1 = cell(*fa.get(1), out.forces_N, "forces");
        const int p0 = cell(*pa.get(0), out.periods_m, "periods"), p1 = cell(*pa.get(1), out.periods_m, "periods");
        if (f0 < 0 || f1 < 0 || p0 < 0 || p1 < 0) continue;
        if (f0 > f1 || p0 > p1) {
          problems.add(f, rt, "a region runs from its first measured value to its last: [low, high]", "");
          continue;
        }
        GroupRegion r;
        std::tie(r.force_min_N, r.force_max_N) = edges(out.forces_N, f0, f1);
        std::tie(r.period_min_m, r.period_max_m) = edges(out.periods_m, p0, p1);
        for (int i = f0; i <= f1; ++i)
          for (int j = p0; j <= p1; ++j) ++covered[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
        for (const auto& s : *rt["stimuli"].as_array()) r.stimuli.push_back(*s.value<std::string>());
        // The listed stimuli must be exactly the measured ones inside the region.
        for (const auto& s : out.stimuli) {
          const bool inside = r.contains(s.force_N, s.period_m);
          const bool listed = std::find(r.stimuli.begin(), r.stimuli.end(), s.name) != r.stimuli.end();
          if (inside && !listed)
            problems.add(f, *rt["stimuli"].node(), "stimulus `" + s.name + "` lies inside this region but is not listed", "add it to `stimuli`");
          if (listed && !inside)
            problems.add(f, *rt["stimuli"].node(), "stimulus `" + s.name + "` is listed but lies outside this region", "");
        }
        for (const auto& name : r.stimuli)
          if (!stimulus_names.count(name))
            problems.add(f, *rt["stimuli"].node(), "`" + name + "` is not a [[measured.stimulus]]", "");
        r.goes_with = str(rt["goes_with"]);
        r.sometimes = str(rt["sometimes"]);
        r.note = str(rt["note"]);
        if (!r.goes_with.empty()) references.emplace_back(rt["goes_with"].node(), r.goes_with);
        if (!r.sometimes.empty()) references.emplace_back(rt["sometimes"].node(), r.sometimes);
        g.regions.push_back(std::move(r));
      }
      grouping.groups.push_back(std::move(g));
    }
    for (const auto& [node, id] : references)
      if (!grouping.find(id)) problems.add(f, *node, "no group `" + id + "` in grouping `" + grouping.id + "`", "");
    for (std::size_t i = 0; i < covered.size(); ++i)
      for (std::size_t j = 0; j < covered[i].size(); ++j)
        if (covered[i][j] != 1)
          problems.add(f, gt,
                       "grouping `" + grouping.id + "`: the measured cell (" + *c["measured"]["forces"][i].value<std::string>() +
                           ", " + *c["measured"]["periods"][j].value<std::string>() + ") is " +
                           (covered[i][j] == 0 ? "in no region" : "in " + std::to_string(covered[i][j]) + " regions"),
                       "the regions of a grouping cover every measured force x period once");
    out.groupings.push_back(std::move(grouping));
  }
}

}  // namespace

void load_knowledge(const std::filesystem::path& dir, const ShownPath& shown, Knowledge& out, Problems& problems,
                    ParsedFileCache* cache) {
  const auto read = [&](const char* name, const std::string& schema) {
    return read_validated(dir / name, shown(dir / name), schema, problems, cache);
  };
  if (auto f = read("force-jnd.toml", "force-jnd")) read_force_jnd(*f, out.force_jnd);
  if (auto f = read("believability.toml", "believability")) read_believability(*f, out.believability, problems);
  if (auto f = read("roughness-groups.toml", "groups")) {
    read_groups(*f, out.roughness_groups, problems);
    for (const char* id : {"period-class", "character"})
      if (!out.roughness_groups.find(id))
        problems.add(*f, f->doc, std::string("no grouping `") + id + "`; the compiler explains with it",
                     "add a [[grouping]] with id = \"" + std::string(id) + "\"");
  }
}

}  // namespace detail
}  // namespace sandpaper::calibration
