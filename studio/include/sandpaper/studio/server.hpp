#pragma once
// The studio's HTTP server (cpp-httplib, Debian's libcpp-httplib-dev): the page, its script, and the
// JSON API of docs/STUDIO.md. Every request passes the Host/Origin guard first; every path it names
// passes the folder confinement. Handlers run on the server's thread pool, never on the servo thread.
#include <atomic>
#include <functional>
#include <memory>
#include <string>

#include "sandpaper/studio/library_browser.hpp"
#include "sandpaper/studio/live_loop.hpp"
#include "sandpaper/http/local_server.hpp"
#include "sandpaper/studio/session.hpp"

namespace sandpaper::studio {

// The page's files, built from studio/web/ by esbuild and compiled in (web_assets.cpp, generated
// by cmake/embed_files.cmake).
using WebAsset = http::Asset;
const std::vector<WebAsset>& web_assets();

class Server {
 public:
  // `library` answers the library browser's requests (/api/library/...).
  Server(Session& session, LiveLoop& loop, LibraryBrowser& library, std::string version);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Binds `listen` (port 0: a free port); returns the bound port. Throws std::runtime_error when the
  // address cannot be bound.
  int bind(const http::Listen& listen);
  // Serves until stop() (from another thread or a signal-watching loop). Blocks.
  void serve();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The /api/state object: {"ticks", "rate_hz", "overruns", "compiled_max_lateral_force_N" (of the
// material playing), "felt_max_lateral_force_N", "material", "material_version", "compiled_roughness",
// "hand": [x_mm, y_mm], "force_N": [fx, fy], "running", "stop_cause", "restarts", "dummy_hand"}.
nlohmann::json state_json(const LoopState& s, bool dummy_hand);

}  // namespace sandpaper::studio
