// Reading experiment designs: TOML validated against schema/files/experiment.schema.json, then
// the checks a schema cannot express (which task needs which section).
#include "sandpaper/experiment/design.hpp"
#include "sandpaper/schema/input_limits.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "sandpaper/schema/file_schema.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::experiment {
namespace {

struct Problems {
  std::string path;
  std::string lines;
  void add(int line, int column, const std::string& message) {
    lines += path + ":" + std::to_string(line) + ":" + std::to_string(column) + ": error: " + message + "\n";
  }
  void add(const toml::node& at, const std::string& message) {
    const auto line = static_cast<int>(at.source().begin.line);
    add(line > 0 ? line : 1, line > 0 ? static_cast<int>(at.source().begin.column) : 1, message);
  }
};

double seconds(const toml::node* n, double fallback) {
  if (!n) return fallback;
  auto q = schema::parse_quantity(*n->value<std::string>());
  return q ? q->si() : fallback;
}

}  // namespace

std::string subject_title_of(const Design& d) {
  if (!d.subject_title.empty()) return d.subject_title;
  switch (d.task) {
    case Task::MagnitudeEstimation: {
      const std::string& p = d.percept;
      const std::string adjective = p == "roughness" ? "rough" : p == "softness" ? "soft" : p == "viscosity" ? "thick"
                                    : p == "slipperiness" ? "slippery" : p;
      return "How " + adjective + " does each surface feel?";
    }
    case Task::Confidence: return "Is it a textured surface?";
    case Task::Sorting: return "Sort the surfaces by feel";
    case Task::TwoInterval: return "Which felt stronger?";
  }
  return "Feeling surfaces";
}

std::vector<std::string> instruction_paragraphs(const std::string& text) {
  std::vector<std::string> out;
  std::string current, line;
  std::istringstream in(text);
  const auto flush = [&] {
    if (!current.empty()) out.push_back(current);
    current.clear();
  };
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) {
      flush();
      continue;
    }
    line = line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
    current += (current.empty() ? "" : " ") + line;
  }
  flush();
  return out;
}

const char* task_name(Task t) noexcept {
  switch (t) {
    case Task::MagnitudeEstimation: return "magnitude-estimation";
    case Task::Confidence: return "confidence";
    case Task::Sorting: return "sorting";
    case Task::TwoInterval: return "two-interval";
  }
  return "?";
}

std::uint64_t fnv1a64(std::string_view bytes) noexcept {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string design_checksum(const std::string& text) {
  const std::uint64_t h = fnv1a64(text);
  char buf[40];
  std::snprintf(buf, sizeof buf, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
  return buf;
}

Design load_design(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw DesignError(path.string() + ": error: no such design file (an experiment design is a .toml file; docs/EXPERIMENTS.md)");
  std::string text;
  try {
    text = schema::read_input_file(path, schema::limits::kMaxTextFileBytes);
  } catch (const schema::InputFileError& e) {
    throw DesignError(path.string() + ": error: cannot read the design file: " + e.reason);
  }
  return parse_design(text, path);
}

Design parse_design(const std::string& text, const std::filesystem::path& path) {
  Problems problems{path.string(), {}};
  toml::table doc;
  try {
    doc = toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    problems.add(static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column),
                 "not valid TOML: " + std::string(e.description()));
    throw DesignError(problems.lines);
  }
  for (const auto& v : schema::validate_file(doc, "experiment"))
    problems.add(v.line, v.column, (v.key.empty() ? "" : "`" + v.key + "`: ") + v.message +
                                       " (schema/files/experiment.schema.json)");
  if (!problems.lines.empty()) throw DesignError(problems.lines);

  Design d;
  d.path = path.string();
  d.text = text;
  d.checksum = design_checksum(text);
  d.title = *doc["title"].value<std::string>();
  d.subject_title = doc["subject_title"].value_or(std::string());
  const std::string task = *doc["task"].value<std::string>();
  d.task = task == "confidence" ? Task::Confidence
           : task == "sorting"  ? Task::Sorting
           : task == "two-interval" ? Task::TwoInterval
                                    : Task::MagnitudeEstimation;
  d.device = doc["device"].value_or(std::string("sim"));
  d.percept = doc["percept"].value_or(std::string("roughness"));
  if (d.percept != "roughness" && d.task != Task::MagnitudeEstimation)
    problems.add(*doc["percept"].node(), "percept = \"" + d.percept + "\" is scaled by magnitude estimation only; "
                                         "use task = \"magnitude-estimation\", or leave percept out (roughness)");
  const auto base = path.parent_path();
  for (const auto& node : *doc["stimuli"].as_array()) {
    StimulusRef s;
    s.text = *node.value<std::string>();
    s.line = static_cast<int>(node.source().begin.line);
    s.column = static_cast<int>(node.source().begin.column);
    const std::filesystem::path p(s.text);
    if (p.extension() == ".hmat") {
      s.file = p.is_absolute() ? p : base / p;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(s.file, ec))
        problems.add(node, "material file `" + s.text + "` not found (looked for " + s.file.string() + ")");
    }
    for (const auto& other : d.stimuli)
      if (other.text == s.text) problems.add(node, "stimulus `" + s.text + "` is listed twice; repetitions repeat the set");
    d.stimuli.push_back(std::move(s));
  }
  d.repetitions = static_cast<int>(doc["repetitions"].value_or(std::int64_t{1}));
  d.seed = static_cast<std::uint64_t>(doc["seed"].value_or(std::int64_t{0}));
  d.practice = static_cast<int>(doc["practice"].value_or(std::int64_t{0}));
  d.break_every = static_cast<int>(doc["break_every"].value_or(std::int64_t{0}));
  d.instructions = *doc["instructions"].value<std::string>();
  if (const auto* pres = doc["presentation"].as_table()) {
    d.duration_s = seconds((*pres)["duration"].node(), d.duration_s);
    d.ramp_s = seconds((*pres)["ramp"].node(), d.ramp_s);
    d.rate_hz = (*pres)["rate_hz"].value_or(d.rate_hz);
    d.hand_speed_m_s = (*pres)["hand_speed_mm_s"].value_or(d.hand_speed_m_s * 1e3) * 1e-3;
    if (const auto* a = (*pres)["hand_amplitude"].node()) {
      auto q = schema::parse_quantity(*a->value<std::string>());
      if (q) d.hand_amplitude_m = q->si();
    }
  }
  const auto* sorting = doc["sorting"].as_table();
  const auto* two = doc["two_interval"].as_table();
  if (d.task == Task::Sorting) {
    if (!sorting) problems.add(doc, "task = \"sorting\" needs a [sorting] table with piles = [2, 3, 4] (thesis 6.2.5)");
    else
      for (const auto& n : *(*sorting)["piles"].as_array()) {
        const int k = static_cast<int>(*n.value<std::int64_t>());
        if (k > static_cast<int>(d.stimuli.size()))
          problems.add(n, "cannot sort " + std::to_string(d.stimuli.size()) + " stimuli into " + std::to_string(k) + " piles");
        d.piles.push_back(k);
      }
    if (d.stimuli.size() < 3) problems.add(*doc["stimuli"].node(), "sorting needs at least 3 stimuli");
  } else if (sorting) {
    problems.add(*doc["sorting"].node(), "[sorting] is for task = \"sorting\"; remove it or change the task");
  }
  if (d.task == Task::TwoInterval) {
    if (!two) problems.add(doc, "task = \"two-interval\" needs a [two_interval] table with increments = [0.05, 0.1, ...]");
    else
      for (const auto& n : *(*two)["increments"].as_array()) d.increments.push_back(*n.value<double>());
    if (d.stimuli.size() != 1)
      problems.add(*doc["stimuli"].node(), "two-interval compares one standard stimulus with stronger copies of itself: "
                                           "give exactly one stimulus");
  } else if (two) {
    problems.add(*doc["two_interval"].node(), "[two_interval] is for task = \"two-interval\"; remove it or change the task");
  }
  if (d.task == Task::MagnitudeEstimation && d.stimuli.size() < 3)
    problems.add(*doc["stimuli"].node(), "magnitude estimation needs at least 3 stimuli to fit a slope");
  if (!problems.lines.empty()) throw DesignError(problems.lines);
  return d;
}

}  // namespace sandpaper::experiment
