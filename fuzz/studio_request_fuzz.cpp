// What the studio reads from a request before any handler runs (http/: request_guard.hpp):
// the Host and Origin headers (the DNS-rebinding and cross-origin guard) and a file path the page
// sends (confined to the studio's folder), plus the --listen address. The input is split at line
// breaks: listen address, Host, Origin, then the path (the rest, line breaks included).
// Each answer is checked against an independent statement of the rule (docs/STUDIO.md, "Safety"):
// an allowed Host names this server exactly; a confined path lies inside the folder, links followed.
// Expected rejections: std::invalid_argument (listen), http::OutsideFolder (path). Nothing else.
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "sandpaper/http/request_guard.hpp"

namespace {

namespace fs = std::filesystem;

// The studio's folder: a material, a subfolder, a link inside it and a link out of it.
const fs::path& studio_root() {
  static const fs::path root = [] {
    const auto r = sandpaper::fuzz::scratch_dir() / "studio";
    fs::create_directories(r / "sub");
    sandpaper::fuzz::write_file(r / "corduroy.hmat", "like corduroy\n");
    sandpaper::fuzz::write_file(r / "sub" / "a.hmat", "roughness 0.5\n");
    std::error_code ec;
    fs::create_directory_symlink(r / "sub", r / "link-in", ec);
    fs::create_directory_symlink(fs::temp_directory_path(), r / "link-out", ec);
    return fs::canonical(r);
  }();
  return root;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool inside(const fs::path& p, const fs::path& root) {
  const std::string ps = p.lexically_normal().string(), rs = root.string();
  return ps == rs || (ps.size() > rs.size() && ps.compare(0, rs.size(), rs) == 0 && ps[rs.size()] == '/');
}

std::string_view next_line(std::string_view& rest) {
  const auto nl = rest.find('\n');
  const auto line = rest.substr(0, nl);
  rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
  return line;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  const std::string listen_text(next_line(rest));
  const std::string_view host = next_line(rest), origin = next_line(rest);
  const std::string relative(rest);

  http::Listen listen;
  listen.port = 4780;
  try {
    listen = http::parse_listen(listen_text);
    fuzz::check(listen.port >= 0 && listen.port <= 65535, "parse_listen gave a port outside 0..65535");
  } catch (const std::invalid_argument&) {
  }

  const std::string why = http::refusal(host, origin, listen);
  if (http::host_allowed(host, listen)) {
    const std::string h = lower(host), port = ":" + std::to_string(listen.port);
    const std::string self = lower(listen.host).find(':') != std::string::npos ? "[" + lower(listen.host) + "]" : lower(listen.host);
    const bool names_this_server = h == self + port ||
        (http::is_loopback(listen.host) && (h == "localhost" + port || h == "127.0.0.1" + port || h == "[::1]" + port));
    fuzz::check(names_this_server, "an allowed Host header that does not name this server: " + h);
  }
  fuzz::check(why.empty() == (http::host_allowed(host, listen) && http::origin_allowed(origin, listen)),
              "refusal() disagrees with host_allowed() and origin_allowed()");

  try {
    const fs::path full = http::confined_path(studio_root(), relative);
    fuzz::check(inside(full, studio_root()), "a confined path outside the studio's folder: " + full.string());
    // Links followed as far as the path exists: what opening or creating the file would reach.
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(full, ec);
    if (!ec) fuzz::check(inside(real, studio_root()), "a confined path whose links lead outside: " + real.string());
  } catch (const http::OutsideFolder&) {
  }
  return 0;
}
