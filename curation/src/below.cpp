#include "below.hpp"

#include "sandpaper/curation/index.hpp"

namespace sandpaper::curation {

std::filesystem::path layer_index_path(const std::filesystem::path& root_dir) { return root_dir / ".index" / "library.sqlite"; }

std::string below_paths(const std::vector<std::filesystem::path>& below) {
  std::string out;
  for (const auto& b : below) out += std::filesystem::absolute(b).lexically_normal().string() + "\n";
  return out;
}

std::optional<std::string> below_fingerprint(const std::vector<std::filesystem::path>& below,
                                             const std::filesystem::path& calibration_dir) {
  std::string out;
  for (std::size_t i = 0; i < below.size(); ++i) {
    const std::vector<std::filesystem::path> under(below.begin() + static_cast<std::ptrdiff_t>(i) + 1, below.end());
    const auto path = layer_index_path(below[i]);
    if (index_state(path, below[i], calibration_dir, under) != IndexState::Fresh) return std::nullopt;
    try {
      out += std::filesystem::absolute(below[i]).lexically_normal().string() + " " + Index(path).meta("fingerprint") + "\n";
    } catch (const IndexError&) {
      return std::nullopt;
    }
  }
  return out;
}

IndexState index_state(const std::filesystem::path& index_path, const std::filesystem::path& library_dir,
                       const std::filesystem::path& calibration_dir) {
  return index_state(index_path, library_dir, calibration_dir, {});
}

IndexState index_state(const std::filesystem::path& index_path, const std::filesystem::path& library_dir,
                       const std::filesystem::path& calibration_dir, const std::vector<std::filesystem::path>& below) {
  const auto own = root_index_state(index_path, library_dir, calibration_dir);
  if (own != IndexState::Fresh) return own;
  try {
    const Index idx(index_path);
    if (idx.meta("below") != below_paths(below)) return IndexState::Stale;
    if (below.empty()) return IndexState::Fresh;
    const auto now = below_fingerprint(below, calibration_dir);
    return now && *now == idx.meta("below_fingerprint") ? IndexState::Fresh : IndexState::Stale;
  } catch (const IndexError&) {
    return IndexState::Stale;
  }
}

}  // namespace sandpaper::curation
