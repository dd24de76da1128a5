// Workspace text (.hws) through the workspace compiler (each patch's material through the material
// compiler), .hmat paths relative to examples/workspace/ so the shipped workspaces' own paths work.
// For a program: written as a .wsp file and read back (the reader must take what the writer wrote),
// written again unchanged, its JSON serialised, and played on the simulated joystick.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <set>
#include <string>

#include "fuzz_compile.hpp"
#include "fuzz_play.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/runtime/workspace_evaluator.hpp"
#include "sandpaper/schema/workspace_io.hpp"
#include "sandpaper/schema/workspace_json.hpp"

namespace {
constexpr std::uint64_t kGridBudget = std::uint64_t{32} << 20;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string text(reinterpret_cast<const char*>(data), size);
  // A force-table budget of 32 MiB rather than 512: the refusal (E0535) is then within the search's
  // reach, and a workspace at the budget stays inside libFuzzer's memory limit under ASan.
  compiler::WorkspaceOptions options;
  options.max_grid_bytes = kGridBudget;
  const auto result = compiler::compile_workspace_text(fuzz::shipped_compiler(), text, "<fuzz>.hws",
                                                       fuzz::source_dir() / "examples" / "workspace", options);
  (void)compiler::format_diagnostics(result.diagnostics);
  fuzz::dump_json(compiler::diagnostics_json(result.diagnostics));
  fuzz::check(!result.program || !result.diagnostics.has_errors(), "a workspace with errors produced a program");
  if (!result.ok()) return 0;
  // The placed programs alone (the compiled materials come on top) must be within the budget.
  std::set<const schema::PatchProgram*> placed;
  std::uint64_t placed_bytes = 0;
  for (const auto& p : result.program->patches)
    if (placed.insert(p.program.get()).second) placed_bytes += schema::grid_bytes(*p.program);
  fuzz::check(placed_bytes <= kGridBudget, "a workspace holding " + std::to_string(placed_bytes) +
                                               " bytes of placed force tables compiled, over its budget");

  const auto wsp = fuzz::scratch_dir() / "workspace.wsp";
  schema::write_workspace_program_file(wsp, *result.program);
  const std::string written = fuzz::read_file(wsp);
  schema::WorkspaceProgram back;
  try {
    back = schema::read_workspace_program_file(wsp);
  } catch (const schema::PatchFormatError& e) {
    if (fuzz::known_defect_tolerated("readback")) return 0;
    fuzz::fail(std::string("a compiled workspace does not read back: ") + e.what());
  }
  schema::write_workspace_program_file(wsp, back);
  fuzz::check(fuzz::read_file(wsp) == written, "write -> read -> write changed a compiled workspace's bytes");
  fuzz::dump_json(schema::to_json(back));

  const auto variant = static_cast<std::uint32_t>(std::hash<std::string>{}(text));
  try {
    runtime::WorkspaceEvaluator evaluator(back);
    const auto report = fuzz::play_and_check(evaluator, variant);
    if (report.stop_cause != runtime::StopCause::Completed && !fuzz::known_defect_tolerated("unplayable"))
      fuzz::fail(std::string("a compiled workspace stops the servo loop: ") + runtime::stop_cause_name(report.stop_cause));
  } catch (const std::invalid_argument& e) {
    if (!fuzz::known_defect_tolerated("unplayable"))
      fuzz::fail(std::string("the runtime refuses a compiled workspace: ") + e.what());
  }
  return 0;
}
