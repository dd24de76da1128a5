#include "subsystems.hpp"

#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "sandpaper/player/exit_codes.hpp"

namespace sandpaper::cli {
namespace {
// One process, one parse: the commands registered by add_unbuilt_command, with their rooms.
std::vector<std::pair<const CLI::App*, Subsystem>>& unbuilt() {
  static std::vector<std::pair<const CLI::App*, Subsystem>> all;
  return all;
}
}  // namespace

void add_unbuilt_command(CLI::App& app, const char* name, const Subsystem& room) {
  auto* sub = app.add_subcommand(name, std::string("not in this build: ") + room.what + " (" + room.option + "=OFF)");
  // Everything after the name, --help included, is left to run_unbuilt_command's message.
  sub->prefix_command();
  sub->allow_extras();
  unbuilt().emplace_back(sub, room);
}

void say_unbuilt(const std::string& who, const Subsystem& room) {
  std::cerr << who << ": this sandpaper was built without " << room.what << " (" << room.folder
            << "). Configure with -D" << room.option << "=ON (the release preset turns every room on) and build again.\n";
}

int run_unbuilt_command(const CLI::App& /*app*/) {
  for (const auto& [sub, room] : unbuilt()) {
    if (!sub->parsed()) continue;
    say_unbuilt("sandpaper " + sub->get_name(), room);
    return kExitUsage;
  }
  return -1;
}

}  // namespace sandpaper::cli
