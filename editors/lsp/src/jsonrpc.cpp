#include "sandpaper/lsp/jsonrpc.hpp"

#include <cctype>
#include <charconv>
#include <istream>
#include <ostream>

namespace sandpaper::lsp {
namespace {

// One header line without its CRLF (a bare LF is accepted too). nullopt at end of input before
// any byte of the line.
std::optional<std::string> header_line(std::istream& in) {
  std::string line;
  for (;;) {
    const int c = in.get();
    if (c == std::char_traits<char>::eof()) {
      if (line.empty()) return std::nullopt;
      throw FramingError("input ended inside a message header");
    }
    if (c == '\n') break;
    if (line.size() >= kMaxHeaderLineBytes) throw FramingError("a header line longer than 1024 bytes");
    line.push_back(static_cast<char>(c));
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

}  // namespace

std::optional<std::string> read_message(std::istream& in) {
  std::optional<std::size_t> length;
  for (int n = 0;; ++n) {
    auto line = header_line(in);
    if (!line) {
      if (n == 0) return std::nullopt;
      throw FramingError("input ended inside a message header");
    }
    if (line->empty()) break;
    if (n >= kMaxHeaderLines) throw FramingError("more than 16 header lines");
    const auto colon = line->find(':');
    if (colon == std::string::npos) throw FramingError("a header line without ':' (" + line->substr(0, 60) + ")");
    const std::string_view name = std::string_view(*line).substr(0, colon);
    std::string_view value = std::string_view(*line).substr(colon + 1);
    while (!value.empty() && (value.front() == ' ' || value.front() == '\t')) value.remove_prefix(1);
    while (!value.empty() && (value.back() == ' ' || value.back() == '\t')) value.remove_suffix(1);
    if (!iequals(name, "Content-Length")) continue;  // Content-Type and anything newer
    std::size_t v = 0;
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), v);
    if (ec != std::errc{} || end != value.data() + value.size() || value.empty())
      throw FramingError("Content-Length is not a whole number of bytes");
    if (v > kMaxMessageBytes) throw FramingError("a message of " + std::to_string(v) + " bytes (at most 20 MiB)");
    length = v;
  }
  if (!length) throw FramingError("a message without Content-Length");
  std::string body(*length, '\0');
  in.read(body.data(), static_cast<std::streamsize>(*length));
  if (static_cast<std::size_t>(in.gcount()) != *length) throw FramingError("input ended inside a message body");
  return body;
}

void write_message(std::ostream& out, const nlohmann::json& message) {
  // Replace, not throw, on invalid UTF-8: a material's bytes can reach messages and hover text.
  const std::string body = message.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  out << "Content-Length: " << body.size() << "\r\n\r\n" << body;
  out.flush();
}

}  // namespace sandpaper::lsp
