#pragma once
// A 3-D scene as the CLI's commands read it: compiled for the options' device, its diagnostics
// printed on stderr (and as JSON on stdout with --json when it fails).
#include <optional>

#include "cli.hpp"
#include "sandpaper/scenes/scene_compiler.hpp"

namespace sandpaper::cli {

std::optional<scenes::SceneResult> load_scene(const CommonOptions& o, const compiler::Compiler& c);

}  // namespace sandpaper::cli
