// Noticing saves (source_watch.hpp).
#include "sandpaper/compiler/source_watch.hpp"

#include <system_error>

namespace sandpaper::compiler {

SourceWatch::SourceWatch(std::filesystem::path file, std::size_t max_text_bytes)
    : file_(std::move(file)), max_text_bytes_(max_text_bytes) {
  seen_ = look(true).value_or(Seen{});
}

std::optional<SourceWatch::Seen> SourceWatch::look(bool read_text) const {
  std::error_code ec;
  Seen now;
  const auto status = std::filesystem::status(file_, ec);
  if (ec || !std::filesystem::exists(status)) return now;  // not there: exists = false
  now.exists = true;
  now.regular = std::filesystem::is_regular_file(status);
  now.stamp = std::filesystem::last_write_time(file_, ec);
  if (ec) return std::nullopt;
  if (now.regular) {
    now.size = std::filesystem::file_size(file_, ec);
    if (ec) return std::nullopt;
  }
  if (!read_text || !now.regular || now.size > max_text_bytes_) return now;
  try {
    now.text = schema::read_input_file(file_, max_text_bytes_);
  } catch (const schema::InputFileError&) {
    return std::nullopt;  // removed or grown since the stat: the next look sees how it ends
  }
  return now;
}

bool SourceWatch::changed() {
  auto now = look(false);
  if (!now || !now->exists) return false;  // removed mid-save: no change until it is back
  const bool racy = std::filesystem::file_time_type::clock::now() - now->stamp < kRacyWindow;
  if (seen_.exists && !racy && now->stamp == seen_.stamp && now->size == seen_.size && now->regular == seen_.regular)
    return false;
  now = look(true);
  if (!now || !now->exists) return false;
  // Compared by text where both looks have it; otherwise by kind, stamp and size.
  const bool differs = !seen_.exists || now->regular != seen_.regular || now->text.has_value() != seen_.text.has_value() ||
                       (now->text ? *now->text != *seen_.text : now->stamp != seen_.stamp || now->size != seen_.size);
  seen_ = std::move(*now);
  return differs;
}

}  // namespace sandpaper::compiler
