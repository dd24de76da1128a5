#include "sandpaper/catalog/html.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

namespace sandpaper::catalog {

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string url_segment(std::string_view text) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : text) {
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '.' || c == '_' ||
        c == '~') {
      out += static_cast<char>(c);
    } else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

std::string json_for_script(const nlohmann::json& data) {
  const std::string s = data.dump();
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '<') out += "\\u003c";
    else if (c == '>') out += "\\u003e";
    else if (c == '&') out += "\\u0026";
    // U+2028 and U+2029 (E2 80 A8/A9 in UTF-8) end a line in older JavaScript parsers.
    else if (static_cast<unsigned char>(c) == 0xE2 && i + 2 < s.size() && static_cast<unsigned char>(s[i + 1]) == 0x80 &&
             (static_cast<unsigned char>(s[i + 2]) == 0xA8 || static_cast<unsigned char>(s[i + 2]) == 0xA9)) {
      out += static_cast<unsigned char>(s[i + 2]) == 0xA8 ? "\\u2028" : "\\u2029";
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

std::string format_number(double value, int digits) {
  if (!std::isfinite(value)) return "n/a";
  if (value == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

std::string json_statement(std::string_view start, const std::string& json_text, std::string_view end) {
  std::string out(start);
  out.reserve(json_text.size() + json_text.size() / 16 + 128);
  // Copied in runs between the characters that need escaping (a data file has few of them).
  for (std::size_t p = 0; p < json_text.size();) {
    const std::size_t q = std::min(json_text.find_first_of("<>\\'", p), json_text.size());
    out.append(json_text, p, q - p);
    if (q == json_text.size()) break;
    const char c = json_text[q];
    if (c == '<') out += "\\\\u003c";  // \u003c in the JSON, its backslash escaped for the string literal
    else if (c == '>') out += "\\\\u003e";
    else out += {'\\', c};
    p = q + 1;
  }
  out += end;
  return out;
}

}  // namespace sandpaper::catalog
