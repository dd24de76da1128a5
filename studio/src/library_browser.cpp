#include "sandpaper/studio/library_browser.hpp"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "sandpaper/catalog/render.hpp"
#include "sandpaper/curation/index.hpp"
#include "sandpaper/curation/progress.hpp"
#include "sandpaper/curation/search.hpp"
#include "sandpaper/studio/session.hpp"

namespace sandpaper::studio {
namespace fs = std::filesystem;
namespace cur = sandpaper::curation;

namespace {

constexpr std::size_t kMaxHits = 30;
constexpr int kPictureSide = 192;

nlohmann::json entry_json(const cur::IndexedEntry& e) {
  return {{"name", e.name},
          {"family", e.family},
          {"describes", e.describes},
          {"aliases", e.aliases},
          {"compiled_roughness", e.roughness},
          {"compiled_max_lateral_force_N", e.max_lateral_force_N},
          {"period_mm", e.period_m > 0 ? nlohmann::json(e.period_m * 1e3) : nlohmann::json(nullptr)},
          {"file", e.file}};
}

// Entry names are words of letters, digits and '-' (LANGUAGE.md): anything else names no entry and
// never reaches a file name.
bool plain_name(const std::string& name) {
  if (name.empty() || name.size() > 200) return false;
  for (char c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) return false;
  return name.front() != '.';
}

}  // namespace

LibraryBrowser::LibraryBrowser(const compiler::Compiler& compiler, fs::path picture_dir)
    : compiler_(compiler), picture_dir_(std::move(picture_dir)) {}

fs::path LibraryBrowser::ensure_index() {
  const fs::path library = compiler_.library().directory();
  const fs::path calibration = compiler_.calibration().directory();
  const fs::path index = cur::default_index_path(library);
  if (cur::index_state(index, library, calibration) == cur::IndexState::Fresh) {
    if (index_state_.empty()) index_state_ = "fresh";
    return index;
  }
  auto progress = cur::Progress::on_stderr("indexing", 0, /*quiet=*/true);
  cur::IndexOptions options{library, calibration, index, "sim"};
  const auto r = cur::build_index(options, progress);
  if (!r.ok)
    throw RequestError(503, "the library's index could not be built: the library has errors (`sandpaper library check` "
                            "says which)");
  index_state_ = "built";
  return index;
}

nlohmann::json LibraryBrowser::search(const std::string& words) {
  std::lock_guard lock(mutex_);
  const cur::Index index(ensure_index());
  cur::SearchQuery q;
  std::istringstream in(words);
  for (std::string w; in >> w;) q.words.push_back(w);
  q.limit = kMaxHits;
  auto out = nlohmann::json::array();
  for (const auto& hit : cur::search(index, q)) out.push_back(entry_json(hit.entry));
  return {{"entries", std::move(out)}, {"index", index_state_}};
}

nlohmann::json LibraryBrowser::entry(const std::string& name) {
  const compiler::LibraryEntry* known = plain_name(name) ? compiler_.library().entry(name) : nullptr;
  if (!known) throw RequestError(404, "no library entry '" + name + "'");
  nlohmann::json j;
  {
    std::lock_guard lock(mutex_);
    const cur::Index index(ensure_index());
    const auto e = index.entry(known->name);
    if (!e) throw RequestError(404, "no library entry '" + name + "' in the index");
    j = entry_json(*e);
  }
  std::ifstream in(known->file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  j["text"] = text.str();
  j["picture"] = picture(known->name).has_value();
  return j;
}

std::optional<fs::path> LibraryBrowser::picture(const std::string& name) {
  const compiler::LibraryEntry* known = plain_name(name) ? compiler_.library().entry(name) : nullptr;
  if (!known) return std::nullopt;
  const fs::path file = picture_dir_ / ("library-" + known->name + ".png");
  std::lock_guard lock(mutex_);
  std::error_code ec;
  if (fs::exists(file, ec)) return file;
  const auto r = compiler_.compile_text(known->name, "<library>");
  if (!r.ok()) return std::nullopt;
  const auto pic = catalog::render_picture(*r.program, kPictureSide);
  if (pic.empty()) return std::nullopt;
  fs::create_directories(picture_dir_, ec);
  catalog::write_png(file, pic);
  return file;
}

}  // namespace sandpaper::studio
