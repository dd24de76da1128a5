// ParsedFileCache (calibration.hpp): parsed, validated calibration files kept with their bytes.
#include <map>
#include <tuple>

#include "file_reading.hpp"

namespace sandpaper::calibration {

struct ParsedFileCache::Entries {
  struct Kept {
    std::string bytes;
    std::shared_ptr<const detail::Toml> file;
  };
  std::map<std::tuple<std::string, std::string>, Kept> by_schema_and_path;
};

ParsedFileCache::ParsedFileCache() : entries_(std::make_unique<Entries>()) {}
ParsedFileCache::~ParsedFileCache() = default;

std::size_t ParsedFileCache::size() const { return entries_->by_schema_and_path.size(); }

std::shared_ptr<const detail::Toml> ParsedFileCache::find(const std::string& schema, const std::filesystem::path& path,
                                                          const std::string& shown_as, const std::string& bytes) {
  const auto it = entries_->by_schema_and_path.find({schema, path.string()});
  if (it == entries_->by_schema_and_path.end() || it->second.bytes != bytes || it->second.file->shown_as != shown_as)
    return nullptr;
  ++hits_;
  return it->second.file;
}

void ParsedFileCache::keep(const std::string& schema, const std::filesystem::path& path, std::string bytes,
                           std::shared_ptr<const detail::Toml> file) {
  entries_->by_schema_and_path[{schema, path.string()}] = {std::move(bytes), std::move(file)};
}

}  // namespace sandpaper::calibration
