#pragma once
// A material file compiled by this tree's compiler, library and calibration, once per file (a
// filtered run compiles only what it times). Header-only, so that bench/compare_revisions.sh can
// build the benches that use it against an older tree too.
#include <filesystem>
#include <map>
#include <memory>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::bench {

// The program compiled from `file` (relative to the source tree, or absolute); nullptr when it
// does not compile.
inline std::shared_ptr<const schema::PatchProgram> compiled_material(const std::filesystem::path& file) {
  static const std::filesystem::path source = SANDPAPER_SOURCE_DIR;
  static std::map<std::filesystem::path, std::shared_ptr<const schema::PatchProgram>> cache;
  auto& slot = cache[file];
  if (!slot) {
    compiler::CompileOptions o;
    o.library_dir = source / "library";
    o.calibration_dir = source / "calibration";
    static const compiler::Compiler c(o);
    auto r = c.compile_file(source / file);
    if (r.ok()) slot = std::make_shared<const schema::PatchProgram>(*r.program);
  }
  return slot;
}

}  // namespace sandpaper::bench
