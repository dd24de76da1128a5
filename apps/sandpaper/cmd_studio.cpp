// `sandpaper studio PATH`: serves the studio page on the loopback address and plays what it edits
// (docs/STUDIO.md). Ctrl-C or SIGTERM stops the servo loop with the force at zero, then the server.
#include <csignal>
#include <cstring>
#include <iostream>
#include <pthread.h>
#include <thread>
#include <unistd.h>

#include "cli.hpp"
#include "sandpaper/runtime/dummy_joystick.hpp"
#include "sandpaper/studio/server.hpp"

#ifndef SANDPAPER_VERSION
#define SANDPAPER_VERSION "0"
#endif

namespace sandpaper::cli {
namespace fs = std::filesystem;

int cmd_studio(const CommonOptions& o_in, const StudioOptions& so) {
  // Every thread started from here on inherits this mask, so SIGINT and SIGTERM reach only the
  // sigtimedwait below: no handler runs on the servo thread and no system call there is interrupted.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  http::Listen listen;
  try {
    listen = http::parse_listen(so.listen);
  } catch (const std::invalid_argument& e) {
    std::cerr << "sandpaper studio: " << e.what() << "\n";
    return kExitUsage;
  }
  std::error_code ec;
  const fs::path given(so.path);
  if (!fs::exists(given, ec)) {
    std::cerr << "sandpaper studio: " << so.path << " does not exist; give a material (.hmat), a workspace (.hws), a scene (.hsc) or a folder\n";
    return kExitUsage;
  }
  const bool folder = fs::is_directory(given, ec);
  if (!folder && given.extension() != ".hmat" && given.extension() != ".hws" && given.extension() != ".hsc") {
    std::cerr << "sandpaper studio: " << so.path << " is not a material (.hmat), a workspace (.hws), a scene (.hsc) or a folder\n";
    return kExitUsage;
  }
  const fs::path root = fs::canonical(folder ? given : fs::absolute(given).parent_path());
  const std::string first = folder ? std::string() : given.filename().string();

  // Data folders given relative to where the studio was started stay valid after the chdir below.
  CommonOptions o = o_in;
  if (!o.library_dir.empty()) o.library_dir = fs::absolute(o.library_dir).string();
  if (!o.calibration_dir.empty()) o.calibration_dir = fs::absolute(o.calibration_dir).string();

  // --device sim plays Dummy mode: the pointer over the preview moves the simulated handle (a real
  // joystick is moved by the hand holding it).
  runtime::DeviceSpec spec;
  spec.device = o.device;
  spec.hand = runtime::SimulatedHand::Pointer;
  spec.watchdog_s = so.guards.watchdog_ms * 1e-3;
  spec.uncalibrated = so.uncalibrated;
  auto joystick = open_device_for(o, std::move(spec), "studio --device " + o.device);
  if (!joystick) return kExitUsage;
  o.device = joystick->calibration;
  const compiler::Compiler compiler = make_compiler(o);
  runtime::DummyJoystick* dummy = joystick->pointer;
  std::unique_ptr<runtime::Device> device = std::move(joystick->device);
  // Material files name their images relative to themselves; the studio compiles from its folder.
  if (::chdir(root.c_str()) != 0) {
    std::cerr << "sandpaper studio: cannot work in " << root << ": " << std::strerror(errno) << "\n";
    return kExitUsage;
  }

  studio::LoopOptions loop_options;
  loop_options.rate_hz = so.rate_hz;
  loop_options.deadline_guard_periods = so.guards.deadline_guard_periods;
  loop_options.velocity_limit_m_s = so.guards.velocity_limit_m_s;
  loop_options.restart_after_fault = dummy != nullptr;
  std::unique_ptr<studio::LiveLoop> loop;
  try {
    loop = std::make_unique<studio::LiveLoop>(std::move(device), dummy, loop_options);
  } catch (const std::invalid_argument& e) {
    std::cerr << "sandpaper studio: " << e.what() << "\n";
    return kExitUsage;
  }
  const fs::path previews = fs::temp_directory_path() / ("sandpaper-studio-" + std::to_string(::getpid()));
  studio::Session session(compiler, *loop, root, previews);
  loop->start_nonrt();
  if (!first.empty()) {
    nlohmann::json opened;
    try {
      opened = session.open(first);
    } catch (const studio::RequestError& e) {
      // A scene in a studio built without the shapes room, or a file it cannot open: said once, and
      // the studio starts on the folder.
      std::cerr << "sandpaper studio: " << first << ": " << e.what() << "\n";
      opened = {{"ok", true}};
    }
    if (!opened["ok"].get<bool>()) {
      for (const auto& d : opened["diagnostics"])
        std::cerr << d["location"].get<std::string>() << ": " << d["severity"].get<std::string>() << "["
                  << d["code"].get<std::string>() << "]: " << d["message"].get<std::string>() << "\n";
      std::cerr << "studio: " << first << " does not compile yet; nothing plays until it does\n";
    }
  }

  studio::LibraryBrowser library(compiler, previews / "library");
  studio::Server server(session, *loop, library, SANDPAPER_VERSION);
  int port = -1;
  try {
    port = server.bind(listen);
  } catch (const std::runtime_error&) {
    // The default port taken (another studio): any free port, rather than no studio.
    if (!so.listen_given) {
      listen.port = 0;
      port = server.bind(listen);
    }
  }
  if (port < 0) {
    std::cerr << "sandpaper studio: cannot listen on " << so.listen << "; try --listen 127.0.0.1:0 for any free port\n";
    loop->stop_nonrt();
    return kExitUsage;
  }
  if (!http::is_loopback(listen.host))
    std::cerr << "warning: the studio listens on " << listen.host
              << ", not a loopback address: anyone who can reach it can play forces on this machine's joystick\n";
  std::thread serving([&server] { server.serve(); });
  const bool v6 = listen.host.find(':') != std::string::npos;
  std::cout << "studio: http://" << (v6 ? "[" + listen.host + "]" : listen.host) << ":" << port << "/" << std::endl;
  std::cout << "  folder " << root.string() << (first.empty() ? "" : ", editing " + first) << "; device "
            << loop->limits().name << (dummy ? " (Dummy mode: the mouse over the preview moves the hand)" : "")
            << "; Ctrl-C stops" << std::endl;

  int sig = 0;
  while (sig <= 0) {
    timespec wait{0, 200'000'000};
    sig = sigtimedwait(&stop_signals, nullptr, &wait);
  }
  // The force first, then the page's server.
  loop->stop_nonrt();
  server.stop();
  serving.join();
  fs::remove_all(previews, ec);
  const auto st = loop->state_nonrt();
  std::cout << "studio: stopped (" << (sig == SIGINT ? "Ctrl-C" : "SIGTERM") << ") after " << st.ticks
            << " ticks; force at zero" << std::endl;
  // The page asks before it closes with edits unsaved; a studio stopped with some keeps each beside
  // its file, and says where. Written nowhere, the text goes to stderr rather than be lost.
  bool all_kept = true;
  for (const auto& u : session.keep_unsaved()) {
    if (u.error.empty()) {
      std::cerr << "studio: " << u.file << " has unsaved edits: not saved to it, kept in " << u.copy
                << " (the studio offers them when it opens " << u.file << " again)\n";
      continue;
    }
    all_kept = false;
    std::cerr << "studio: " << u.file << " has unsaved edits that could not be kept beside it (" << u.error
              << "); its text follows, between the lines of dashes\n-----\n"
              << u.text << (u.text.ends_with('\n') ? "" : "\n") << "-----\n";
  }
  return all_kept ? kExitOk : kExitUsage;
}

}  // namespace sandpaper::cli
