#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::schema {

std::string read_input_file(const std::filesystem::path& path, std::size_t max_bytes) {
  const std::string name = path.string();
  // Before opening: opening a FIFO blocks until a writer comes, and /dev/zero never ends.
  struct stat st{};
  if (::stat(name.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode))
    throw InputFileError(name, "not a regular file (a device, FIFO or socket); give a file on disk");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(name.c_str(), "rb"), &std::fclose);
  if (!f) throw InputFileError(name, std::strerror(errno));
  // Again on the open file: a file swapped in after the first check must not slip through.
  if (fstat(fileno(f.get()), &st) != 0) throw InputFileError(name, std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw InputFileError(name, "a directory, not a file");
  if (!S_ISREG(st.st_mode))
    throw InputFileError(name, "not a regular file (a device, FIFO or socket); give a file on disk");
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes)
    throw InputFileError(name, std::to_string(size) + " bytes, over the limit of " + std::to_string(max_bytes) +
                                   " bytes for this kind of file (docs/RELIABILITY.md)");
  std::string text(static_cast<std::size_t>(size), '\0');
  const std::size_t got = size ? std::fread(text.data(), 1, text.size(), f.get()) : 0;
  if (got != text.size() || std::ferror(f.get())) throw InputFileError(name, "read failed");
  // A file that grew while we read it: refuse rather than take part of it.
  if (std::fgetc(f.get()) != EOF) throw InputFileError(name, "changed while it was read; try again");
  return text;
}

bool is_valid_utf8(std::string_view s, std::size_t& bad_offset) noexcept {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  std::size_t i = 0;
  while (i < n) {
    const unsigned char c = p[i];
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len = 0;
    std::uint32_t cp = 0, min = 0;
    if ((c & 0xE0) == 0xC0) len = 2, cp = c & 0x1Fu, min = 0x80;
    else if ((c & 0xF0) == 0xE0) len = 3, cp = c & 0x0Fu, min = 0x800;
    else if ((c & 0xF8) == 0xF0) len = 4, cp = c & 0x07u, min = 0x10000;
    else {
      bad_offset = i;
      return false;
    }
    if (n - i < len) {
      bad_offset = i;
      return false;
    }
    for (std::size_t k = 1; k < len; ++k) {
      if ((p[i + k] & 0xC0) != 0x80) {
        bad_offset = i;
        return false;
      }
      cp = (cp << 6) | (p[i + k] & 0x3Fu);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) {
      bad_offset = i;
      return false;
    }
    i += len;
  }
  return true;
}

std::string replace_invalid_utf8(std::string_view text) {
  std::string out;
  std::size_t bad = 0;
  while (!is_valid_utf8(text, bad)) {
    out.append(text.substr(0, bad));
    out.append("\xEF\xBF\xBD");  // U+FFFD for the byte that does not start a whole character
    text.remove_prefix(bad + 1);
  }
  out.append(text);
  return out;
}

}  // namespace sandpaper::schema
