#pragma once
// Reading calibration TOML files: parse, validate against the file schema, and collect every
// problem as "file:line:col: error: message" so one load reports all of them.
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "sandpaper/calibration/calibration.hpp"

namespace sandpaper::calibration::detail {

struct Toml {
  std::string shown_as;  // path as shown in messages and provenance
  toml::table doc;
};

class Problems {
 public:
  void add(const Toml& f, const toml::node& at, const std::string& message, const std::string& help);
  void add_at(const std::string& file, int line, int column, const std::string& message);
  void add_plain(const std::string& message) { lines_.push_back(message); }
  bool any() const { return !lines_.empty(); }
  std::size_t count() const { return lines_.size(); }
  void throw_if_any() const;

 private:
  std::vector<std::string> lines_;
};

// Parses `path` and validates it against schema `schema_name`; null (with problems added) if the
// file is missing, not TOML, or violates its schema. With `cache`, a kept file of the same bytes is
// returned without parsing, and a valid file is kept while the cache learns.
std::shared_ptr<const Toml> read_validated(const std::filesystem::path& path, const std::string& shown_as,
                                           const std::string& schema_name, Problems& problems,
                                           ParsedFileCache* cache = nullptr);

// The same for text already read: `shown_as` names it in messages.
std::shared_ptr<const Toml> parse_validated(const std::string& text, const std::string& shown_as,
                                            const std::string& schema_name, Problems& problems);

// A validated quantity string ("382 gf") in SI.
double quantity_si(const toml::node& n);

using ShownPath = std::function<std::string(const std::filesystem::path&)>;
// Reads calibration/knowledge/*.toml into `out` (knowledge.cpp).
void load_knowledge(const std::filesystem::path& dir, const ShownPath& shown, Knowledge& out, Problems& problems,
                    ParsedFileCache* cache);

}  // namespace sandpaper::calibration::detail
