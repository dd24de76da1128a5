#pragma once
// `sandpaper library check|index|search|show|near` (docs/LIBRARY.md). `sandpaper library`
// with no subcommand lists the entries (cmd_compile.cpp, cmd_library).
#include <cstddef>
#include <string>
#include <vector>

#include "cli.hpp"

namespace CLI {
class App;
}

namespace sandpaper::cli {

struct LibraryCommandOptions {
  std::string library_dir, calibration_dir, index;  // empty: as the parent `library` command, or defaults
  bool json = false, quiet = false, werror = false, full = false;  // full: index compiles every entry
  std::vector<std::string> devices;                  // check: empty = every device of the calibration
  std::vector<std::string> words;                    // search
  std::string roughness, family;                     // search filters
  std::size_t limit = 20;                            // search, near
  std::string name;                                  // show, near
  std::string root;                                  // check: only this root of a layered library
  std::vector<std::string> changed;                  // index: the files that changed ("-": read from stdin)
  std::string base = "HEAD";                         // review: the commit to compare with
  CLI::App *check = nullptr, *index_cmd = nullptr, *search = nullptr, *show = nullptr, *near = nullptr, *review = nullptr;
};

// Registers the subcommands on the `library` command.
void add_library_commands(CLI::App& library, LibraryCommandOptions& o);
// Runs whichever subcommand was parsed; -1 if none was. `common` carries the parent's --library etc.
int cmd_library_sub(const CommonOptions& common, LibraryCommandOptions o);

}  // namespace sandpaper::cli
