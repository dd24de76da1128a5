#pragma once
// Noticing that a material file was saved again, for `sandpaper run FILE --watch` (docs/STUDIO.md).
// A file's modification stamp alone misses saves: an editor truncates the file and writes it, and
// the file system stamps both from a coarse clock (ext4: one kernel tick, a few milliseconds), so a
// look between the two reads the empty file under the stamp the full one keeps. The size catches
// that case; a same-size save within the same tick is caught by reading the text again while the
// stamp is "racy" (younger than kRacyWindow), as git does for its index.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace sandpaper::compiler {

class SourceWatch {
 public:
  // A stamp younger than this may hide a later write with the same stamp.
  static constexpr std::chrono::seconds kRacyWindow{2};

  // Takes the file's text as it is now as seen (an unreadable file: as empty).
  explicit SourceWatch(std::filesystem::path file);

  // The file's text if it differs from the text last seen; nullopt if it is the same, or if the file
  // cannot be read now (a save in progress that removed it: the next look sees it). Stats the file
  // each call and reads it only when its stamp or size changed or its stamp is racy.
  std::optional<std::string> changed_text();

  const std::filesystem::path& file() const { return file_; }

 private:
  std::filesystem::path file_;
  std::filesystem::file_time_type stamp_{};
  std::uintmax_t size_ = 0;
  std::string text_;
};

}  // namespace sandpaper::compiler
