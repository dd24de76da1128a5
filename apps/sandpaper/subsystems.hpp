#pragma once
// The optional rooms a `sandpaper` may be built without (docs/ARCHITECTURE.md, CMake options
// SANDPAPER_<NAME>). A command whose room was left out is still listed in --help, and running it
// says which option builds it, instead of "unknown command".
#include <string>

namespace CLI {
class App;
}

namespace sandpaper::cli {

struct Subsystem {
  const char* what;    // as a user names it: "Sandpaper Studio"
  const char* option;  // the CMake option that builds it
  const char* folder;  // its room in the source tree
};
inline constexpr Subsystem kCuration{"the curator's tools (library check, index, search, catalog, preview)",
                                     "SANDPAPER_CURATION", "curation/"};
inline constexpr Subsystem kGltf{"glTF 2.0 import and export", "SANDPAPER_GLTF", "compiler/src/interop/gltf_*.cpp"};
inline constexpr Subsystem kStudio{"Sandpaper Studio", "SANDPAPER_STUDIO", "studio/"};
inline constexpr Subsystem kLsp{"the language server", "SANDPAPER_LSP", "editors/lsp/"};
inline constexpr Subsystem kExperiments{"the experiments with people", "SANDPAPER_EXPERIMENTS", "experiments/"};
inline constexpr Subsystem kShapes{"3-D scenes (scene files, glTF scenes, the proxy renderer)", "SANDPAPER_SHAPES", "shapes/, scenes/"};

// Registers `name` on `app` as a command that takes any arguments and only reports that `room` is missing.
void add_unbuilt_command(CLI::App& app, const char* name, const Subsystem& room);
// Prints "<who>: this sandpaper was built without <room> ..., configure with -D<option>=ON" to stderr.
void say_unbuilt(const std::string& who, const Subsystem& room);
// If one of those was given: says so on stderr and returns 2 (kExitUsage); else -1.
int run_unbuilt_command(const CLI::App& app);

}  // namespace sandpaper::cli
