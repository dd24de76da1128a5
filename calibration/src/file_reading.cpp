#include "file_reading.hpp"
#include "sandpaper/schema/input_limits.hpp"

#include "sandpaper/schema/file_schema.hpp"
#include "sandpaper/schema/units.hpp"

namespace sandpaper::calibration::detail {

void Problems::add(const Toml& f, const toml::node& at, const std::string& message, const std::string& help) {
  const auto& src = at.source();
  add_at(f.shown_as, static_cast<int>(src.begin.line), static_cast<int>(src.begin.column),
         message + (help.empty() ? "" : "; " + help));
}

void Problems::add_at(const std::string& file, int line, int column, const std::string& message) {
  if (line <= 0) line = column = 1;
  lines_.push_back(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": error: " + message);
}

void Problems::throw_if_any() const {
  if (lines_.empty()) return;
  std::string all;
  for (const auto& l : lines_) all += (all.empty() ? "" : "\n") + l;
  throw CalibrationError(all);
}

std::shared_ptr<const Toml> read_validated(const std::filesystem::path& path, const std::string& shown_as,
                                           const std::string& schema_name, Problems& problems, ParsedFileCache* cache) {
  if (!std::filesystem::exists(path)) {
    problems.add_plain(shown_as + ": error: calibration file missing");
    return nullptr;
  }
  std::string text;
  try {
    text = schema::read_input_file(path, schema::limits::kMaxTextFileBytes);
  } catch (const schema::InputFileError& e) {
    problems.add_plain(shown_as + ": error: cannot read: " + e.reason);
    return nullptr;
  }
  // The path shown is part of what is kept: it is in every message the file's values give later.
  if (cache)
    if (auto kept = cache->find(schema_name, path, shown_as, text)) return kept;
  auto f = parse_validated(text, shown_as, schema_name, problems);
  if (f && cache && cache->learning()) cache->keep(schema_name, path, std::move(text), f);
  return f;
}

std::shared_ptr<const Toml> parse_validated(const std::string& text, const std::string& shown_as,
                                            const std::string& schema_name, Problems& problems) {
  auto f = std::make_shared<Toml>(Toml{shown_as, {}});
  try {
    f->doc = toml::parse(text, shown_as);
  } catch (const toml::parse_error& e) {
    problems.add_at(shown_as, static_cast<int>(e.source().begin.line), static_cast<int>(e.source().begin.column),
                    "not valid TOML: " + std::string(e.description()));
    return nullptr;
  }
  auto violations = schema::validate_file(f->doc, schema_name);
  for (const auto& v : violations)
    problems.add_at(shown_as, v.line, v.column,
                    (v.key.empty() ? "" : "`" + v.key + "`: ") + v.message + " (schema/files/" + schema_name + ".schema.json)");
  if (!violations.empty()) return nullptr;
  return f;
}

double quantity_si(const toml::node& n) {
  auto q = schema::parse_quantity(*n.value<std::string>());
  return q ? q->si() : 0.0;
}

}  // namespace sandpaper::calibration::detail
