// Noticing saves (source_watch.hpp).
#include "sandpaper/compiler/source_watch.hpp"

#include <fstream>
#include <iterator>

namespace sandpaper::compiler {

namespace {

std::optional<std::string> read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return std::nullopt;
  return text;
}

}  // namespace

SourceWatch::SourceWatch(std::filesystem::path file) : file_(std::move(file)) {
  std::error_code ec;
  stamp_ = std::filesystem::last_write_time(file_, ec);
  size_ = ec ? 0 : std::filesystem::file_size(file_, ec);
  text_ = read_text(file_).value_or(std::string());
}

std::optional<std::string> SourceWatch::changed_text() {
  std::error_code ec;
  const auto stamp = std::filesystem::last_write_time(file_, ec);
  if (ec) return std::nullopt;
  const auto size = std::filesystem::file_size(file_, ec);
  if (ec) return std::nullopt;
  const bool racy = std::filesystem::file_time_type::clock::now() - stamp < kRacyWindow;
  if (stamp == stamp_ && size == size_ && !racy) return std::nullopt;
  auto text = read_text(file_);
  if (!text) return std::nullopt;
  // The stamp and size of what was read (a write between the stat and the read shows at the next look:
  // its stamp is racy then).
  stamp_ = stamp;
  size_ = size;
  if (*text == text_) return std::nullopt;
  text_ = *text;
  return text;
}

}  // namespace sandpaper::compiler
