#pragma once
// What keeps a web page elsewhere from driving a joystick through a local server (the studio, an
// experiment's subject page), and the studio inside the folder it was opened on (docs/STUDIO.md,
// "Safety"). Pure functions, so they are tested directly.
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "sandpaper/schema/confined_path.hpp"

namespace sandpaper::http {

// The address the server listens on, and the names a browser may use for it.
struct Listen {
  std::string host = "127.0.0.1";
  int port = 0;  // 0: any free port (the bound one is filled in after binding)
};
// Parses "ADDR:PORT" ("127.0.0.1:4780", "[::1]:0", "localhost:8000"); throws std::invalid_argument.
Listen parse_listen(const std::string& text);
// Whether `host` is a loopback address or name (127.0.0.0/8, ::1, localhost).
bool is_loopback(std::string_view host);

// A request's Host header must name this server: "<listen host>:<port>", or, when it listens on a
// loopback address, "localhost:<port>", "127.0.0.1:<port>" or "[::1]:<port>". Anything else, a
// missing header included, is refused (DNS rebinding: a foreign name resolving to 127.0.0.1).
bool host_allowed(std::string_view host_header, const Listen& listen);
// An Origin header, when present, must be "http://" followed by an allowed host. Absent (curl, a
// script, a same-origin GET) passes: browsers send Origin on every cross-origin request and POST.
bool origin_allowed(std::string_view origin_header, const Listen& listen);
// Both checks: "" when a request with these headers may proceed, else why it is refused (for a 403).
std::string refusal(std::string_view host_header, std::string_view origin_header, const Listen& listen);

// A path given by a page or a script, refused unless it stays inside the served folder.
using schema::OutsideFolder;
// `relative` resolved inside `root` (which must exist), symbolic links followed (schema::confined_path).
// Throws OutsideFolder for an absolute path, a path that climbs out with "..", or a link that points outside.
std::filesystem::path confined_path(const std::filesystem::path& root, const std::string& relative);

}  // namespace sandpaper::http
