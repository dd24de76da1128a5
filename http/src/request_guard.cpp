#include "sandpaper/http/request_guard.hpp"

#include <algorithm>
#include <charconv>

namespace sandpaper::http {

Listen parse_listen(const std::string& text) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size())
    throw std::invalid_argument("--listen takes ADDR:PORT, e.g. 127.0.0.1:4780 (port 0: any free port)");
  Listen l;
  l.host = text.substr(0, colon);
  if (l.host.size() > 2 && l.host.front() == '[' && l.host.back() == ']') l.host = l.host.substr(1, l.host.size() - 2);
  const std::string port = text.substr(colon + 1);
  const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), l.port);
  if (ec != std::errc() || end != port.data() + port.size() || l.port < 0 || l.port > 65535)
    throw std::invalid_argument("--listen: '" + port + "' is not a port number (0 to 65535)");
  return l;
}

bool is_loopback(std::string_view host) {
  return host == "localhost" || host == "::1" || host.substr(0, 4) == "127.";
}

namespace {

std::string with_port(std::string_view host, int port) {
  const bool v6 = host.find(':') != std::string_view::npos;
  return (v6 ? "[" + std::string(host) + "]" : std::string(host)) + ":" + std::to_string(port);
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

}  // namespace

bool host_allowed(std::string_view host_header, const Listen& listen) {
  const std::string h = lower(host_header);
  if (h.empty()) return false;
  if (h == with_port(lower(listen.host), listen.port)) return true;
  if (!is_loopback(listen.host)) return false;
  for (const char* name : {"localhost", "127.0.0.1", "::1"})
    if (h == with_port(name, listen.port)) return true;
  return false;
}

bool origin_allowed(std::string_view origin_header, const Listen& listen) {
  if (origin_header.empty()) return true;
  const std::string o = lower(origin_header);
  constexpr std::string_view scheme = "http://";
  if (o.substr(0, scheme.size()) != scheme) return false;
  return host_allowed(std::string_view(o).substr(scheme.size()), listen);
}

std::filesystem::path confined_path(const std::filesystem::path& root, const std::string& relative) {
  return schema::confined_path(root, relative, "the studio's folder",
                               "the studio reads and writes only inside the folder it was opened on");
}

std::string refusal(std::string_view host_header, std::string_view origin_header, const Listen& listen) {
  if (!host_allowed(host_header, listen))
    return "refused: Host '" + std::string(host_header) + "' is not this server's address; open the address it printed";
  if (!origin_allowed(origin_header, listen))
    return "refused: requests from origin '" + std::string(origin_header) + "' may not drive this server";
  return "";
}

}  // namespace sandpaper::http
