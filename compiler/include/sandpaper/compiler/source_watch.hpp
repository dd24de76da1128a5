#pragma once
// Noticing that a material file was saved again, for `sandpaper run FILE --watch` (docs/STUDIO.md).
// A file's modification stamp alone misses saves: an editor truncates the file and writes it, and
// the file system stamps both from a coarse clock (ext4: one kernel tick, a few milliseconds), so a
// look between the two reads the empty file under the stamp the full one keeps. The size catches
// that case; a same-size save within the same tick is caught by reading the text again while the
// stamp is "racy" (younger than kRacyWindow), as git does for its index.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {

class SourceWatch {
 public:
  // A stamp younger than this may hide a later write with the same stamp.
  static constexpr std::chrono::seconds kRacyWindow{2};

  // Takes the file as it is now as seen. Its text is read and compared only while it is a regular
  // file of at most `max_text_bytes` (the limit of the reader the caller then uses, so reading here
  // is bounded as that reader is; docs/RELIABILITY.md): past it, or when it is not a regular file
  // (a FIFO, a device: opening one could block the watch), its stamp and size stand for its text,
  // and the caller's reader reports what is wrong.
  explicit SourceWatch(std::filesystem::path file, std::size_t max_text_bytes = schema::limits::kMaxSourceBytes);

  // True if the file differs from how it was last seen, once per change; false if it is the same,
  // or cannot be looked at now (a save in progress that removed it: the next look sees it). Stats
  // the file each call and reads it only when its stamp, size or kind changed, or its stamp is racy.
  bool changed();

  const std::filesystem::path& file() const { return file_; }

 private:
  struct Seen {
    bool exists = false;
    bool regular = false;
    std::filesystem::file_time_type stamp{};
    std::uintmax_t size = 0;
    std::optional<std::string> text;  // nullopt: not compared by text (see the constructor)
  };
  // How the file is now; nullopt if it could not be looked at (removed, or grew past the limit,
  // between the stat and the read).
  std::optional<Seen> look(bool read_text) const;

  std::filesystem::path file_;
  std::size_t max_text_bytes_;
  Seen seen_;
};

}  // namespace sandpaper::compiler
