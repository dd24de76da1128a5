#include "sandpaper/lsp/text_positions.hpp"

#include <algorithm>

namespace sandpaper::lsp {
namespace {

// Length of the UTF-8 sequence led by `lead`, or 1 for a byte that cannot lead one.
std::size_t sequence_length(unsigned char lead) {
  if (lead < 0x80) return 1;
  if ((lead >> 5) == 0x6) return 2;
  if ((lead >> 4) == 0xE) return 3;
  if ((lead >> 3) == 0x1E) return 4;
  return 1;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

int utf16_units(std::string_view line, std::size_t byte_column) {
  byte_column = std::min(byte_column, line.size());
  int units = 0;
  for (std::size_t i = 0; i < byte_column;) {
    const std::size_t n = sequence_length(static_cast<unsigned char>(line[i]));
    units += n == 4 ? 2 : 1;  // outside the Basic Multilingual Plane: a surrogate pair
    i += n;
  }
  return units;
}

std::size_t byte_offset(std::string_view line, int units) {
  std::size_t i = 0;
  for (int u = 0; u < units && i < line.size();) {
    const std::size_t n = sequence_length(static_cast<unsigned char>(line[i]));
    u += n == 4 ? 2 : 1;
    i += n;
  }
  return std::min(i, line.size());
}

nlohmann::json range_of(const compiler::SourceLocation& loc, const compiler::SourceFile& file) {
  const bool here = loc.file && (loc.file.get() == &file || loc.file->name == file.name) && loc.line > 0;
  if (!here) return {{"start", {{"line", 0}, {"character", 0}}}, {"end", {{"line", 0}, {"character", 0}}}};
  const std::string_view text = file.line_text(loc.line);
  const std::size_t start = static_cast<std::size_t>(std::max(1, loc.column) - 1);
  const std::size_t end = start + static_cast<std::size_t>(std::max(1, loc.length));
  const int line = loc.line - 1;
  return {{"start", {{"line", line}, {"character", utf16_units(text, start)}}},
          {"end", {{"line", line}, {"character", utf16_units(text, end)}}}};
}

std::string path_of_uri(std::string_view uri) {
  constexpr std::string_view scheme = "file://";
  if (uri.substr(0, scheme.size()) != scheme) return {};
  uri.remove_prefix(scheme.size());
  // file://host/path: only the local host (empty or "localhost") is a path here.
  const auto slash = uri.find('/');
  if (slash == std::string_view::npos) return {};
  if (const auto host = uri.substr(0, slash); !host.empty() && host != "localhost") return {};
  uri.remove_prefix(slash);
  std::string path;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size()) {
      const int hi = hex_value(uri[i + 1]), lo = hex_value(uri[i + 2]);
      if (hi >= 0 && lo >= 0) {
        path.push_back(static_cast<char>(hi * 16 + lo));
        i += 2;
        continue;
      }
    }
    if (uri[i] == '?' || uri[i] == '#') break;
    path.push_back(uri[i]);
  }
  return path;
}

std::string uri_of_path(std::string_view absolute_path) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string uri = "file://";
  for (const char ch : absolute_path) {
    const auto c = static_cast<unsigned char>(ch);
    const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                       c == '.' || c == '_' || c == '~' || c == '/';
    if (plain) {
      uri.push_back(ch);
    } else {
      uri.push_back('%');
      uri.push_back(kHex[c >> 4]);
      uri.push_back(kHex[c & 0xF]);
    }
  }
  return uri;
}

}  // namespace sandpaper::lsp
