// Installing a fitted device map: what it would change, found by compiling before and after.
#include "sandpaper/experiment/map_install.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "sandpaper/compiler/percepts.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::experiment {
namespace {

namespace fs = std::filesystem;

// The word a percept is written with and the provenance name of what it sets.
struct Word {
  std::vector<std::string> spellings;
  std::string parameter, unit;
};

Word word_of(const std::string& percept) {
  if (percept == "roughness") return {{"roughness"}, "texture.max_lateral_force", "N"};
  Word w;
  for (const auto& p : compiler::percept_words())
    if (p.percept == percept) {
      w.spellings.push_back(p.word);
      w.parameter = p.parameter;
      w.unit = p.si_unit;
    }
  return w;
}

CompileOutcome outcome(const compiler::Compiler& c, const std::string& text, const std::string& parameter) {
  CompileOutcome o;
  const auto r = c.compile_text(text);
  o.ok = r.ok();
  for (const auto& d : r.diagnostics.all()) o.codes.push_back(d.code);
  if (r.program)
    for (const auto& p : r.program->provenance)
      if (p.parameter == parameter) o.value_si = p.value_si;
  return o;
}

std::string shown(const CompileOutcome& o, const std::string& unit) {
  std::string s = o.ok ? schema::display_value(o.value_si, unit) : std::string("does not compile");
  if (!o.codes.empty()) s += fmt::format(" ({})", fmt::join(o.codes, ", "));
  return s;
}

}  // namespace

bool MapChange::changed() const {
  if (before.ok != after.ok || before.codes != after.codes) return true;
  const double scale = std::max(std::abs(before.value_si), std::abs(after.value_si));
  return scale > 0 && std::abs(before.value_si - after.value_si) > 1e-6 * scale;
}

calibration::CalibrationSet calibration_with_map(const fs::path& dir, const std::string& file_name,
                                                 const std::string& map_text, const calibration::PsychophysicalMap& map) {
  static std::atomic<int> counter{0};
  const fs::path tmp = fs::temp_directory_path() / fmt::format("sandpaper-map-install-{}-{}", ::getpid(), counter++);
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{tmp};
  fs::create_directories(tmp);
  const fs::path copy = tmp / "calibration";
  fs::copy(dir, copy, fs::copy_options::recursive);
  for (const auto& e : fs::directory_iterator(copy / "maps")) {
    if (e.path().extension() != ".toml") continue;
    bool replaced = e.path().filename() == file_name;
    try {
      const auto m = calibration::load_map_file(e.path());
      replaced = replaced || m.id == map.id ||
                 (m.for_device && map.for_device && m.domain_device == map.domain_device && m.percept == map.percept);
    } catch (const calibration::CalibrationError&) {
      // the set below reports its own broken files
    }
    if (replaced) fs::remove(e.path());
  }
  std::ofstream(copy / "maps" / file_name, std::ios::binary) << map_text;
  return calibration::CalibrationSet::load(copy);
}

std::vector<double> level_values(const calibration::CalibrationSet& cal, const calibration::PsychophysicalMap& map) {
  std::vector<double> out;
  if (map.percept == "roughness")
    for (const auto& l : cal.roughness_levels()) out.push_back(map.value_for(l.value));
  else
    for (const auto* l : cal.levels(map.percept)) out.push_back(map.value_for(l->value));
  return out;
}

std::vector<MapChange> map_changes(const compiler::Compiler& before, const compiler::Compiler& after,
                                   const std::string& percept) {
  const Word w = word_of(percept);
  std::vector<MapChange> out;
  if (w.spellings.empty()) return out;
  std::vector<std::string> names;
  if (percept == "roughness")
    for (const auto& l : after.calibration().roughness_levels()) names.push_back(l.name);
  else
    for (const auto* l : after.calibration().levels(percept)) names.push_back(l->name);
  for (const auto& name : names) {
    MapChange c;
    c.kind = "level";
    c.name = name;
    // A roughness needs a texture to set the force of; the other words stand alone.
    c.text = percept == "roughness" ? "grating period 2.5 mm; roughness " + name : w.spellings.front() + " " + name;
    c.unit = w.unit;
    c.before = outcome(before, c.text, w.parameter);
    c.after = outcome(after, c.text, w.parameter);
    out.push_back(std::move(c));
  }
  std::string alternatives;
  for (const auto& s : w.spellings) alternatives += (alternatives.empty() ? "" : "|") + s;
  const std::regex statement("(^|[\\n;])[ \\t]*(" + alternatives + ")\\b");
  for (const auto& e : before.library().entries()) {
    std::ifstream in(e.file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (!std::regex_search(text.str(), statement)) continue;
    MapChange c;
    c.kind = "library";
    c.name = e.name;
    c.text = e.name;
    c.unit = w.unit;
    c.before = outcome(before, c.text, w.parameter);
    c.after = outcome(after, c.text, w.parameter);
    out.push_back(std::move(c));
  }
  return out;
}

nlohmann::json map_changes_json(const std::vector<MapChange>& changes) {
  nlohmann::json out = nlohmann::json::array();
  const auto side = [](const CompileOutcome& o) {
    return nlohmann::json{{"ok", o.ok}, {"value", o.ok ? nlohmann::json(o.value_si) : nlohmann::json(nullptr)}, {"codes", o.codes}};
  };
  for (const auto& c : changes)
    out.push_back({{"kind", c.kind}, {"name", c.name}, {"text", c.text}, {"unit", c.unit}, {"before", side(c.before)},
                   {"after", side(c.after)}, {"breaks", c.breaks()}, {"changed", c.changed()}});
  return out;
}

std::string map_changes_text(const std::vector<MapChange>& changes) {
  std::string out;
  for (const auto& c : changes) {
    if (!c.changed()) continue;
    out += fmt::format("  {} `{}`: {} -> {}{}\n", c.kind, c.text, shown(c.before, c.unit), shown(c.after, c.unit),
                       c.breaks() ? ": BREAKS" : "");
  }
  return out;
}

}  // namespace sandpaper::experiment
