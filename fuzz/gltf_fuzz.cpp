// glTF assets (`sandpaper compile ASSET.gltf`, compiler/gltf_import.hpp) through the reader: any
// bytes give a program, a workspace or diagnostics, never a crash or an unbounded allocation; a
// program it accepts must pass every compiled program's checks (written, read back, played within
// the device's clamp: fuzz_compile.hpp), and so must each patch of a workspace it accepts.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <set>
#include <string>

#include "fuzz_compile.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/compiler/gltf_import.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const auto r = compiler::import_gltf_text(fuzz::shipped_compiler(), bytes, "<fuzz>.gltf");
  (void)compiler::format_diagnostics(r.diagnostics);
  fuzz::check(r.ok() || (!r.program && !r.workspace), "an import with errors produced a program");
  fuzz::check(!(r.program && r.workspace), "an import produced both a material and a workspace");
  const auto variant = static_cast<std::uint32_t>(std::hash<std::string>{}(bytes));
  if (r.program) fuzz::check_compiled_program(*r.program, variant);
  if (r.workspace) {
    std::set<const schema::PatchProgram*> seen;  // patches of one haptic material share a program
    for (const auto& p : r.workspace->patches)
      if (seen.insert(p.program.get()).second) fuzz::check_compiled_program(*p.program, variant);
  }
  return 0;
}
