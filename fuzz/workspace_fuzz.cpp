// Workspace text (.hws) through the workspace compiler (each patch's material through the material
// compiler), .hmat paths relative to examples/workspace/ so the shipped workspaces' own paths work.
// For a program: written as a .wsp file and read back (the reader must take what the writer wrote),
// written again unchanged, its JSON serialised, and played on the simulated joystick.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>

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

// Materials compiled for earlier inputs, by (.hmat or text, name shown). Most inputs keep most of a
// seed's patches ("gravel", "corduroy", ...), and recompiling them was two thirds of the harness's
// time (perf, docs/RELIABILITY.md). A compile depends only on these and on files nothing here
// writes (the library, its images, the .hmat), so a kept result is what a compile would give now,
// and an input replayed alone compiles it afresh to the same result. Bounded: cleared when full.
class MaterialMemo {
 public:
  std::shared_ptr<const sandpaper::compiler::CompileResult> compile(const sandpaper::compiler::Compiler& compiler,
                                                                    const sandpaper::compiler::WorkspaceMaterial& m) {
    auto key = std::make_pair(m.file.empty() ? "text:" + m.text : "file:" + m.file.string(), m.display_name);
    if (auto it = kept_.find(key); it != kept_.end()) return it->second;
    auto r = sandpaper::compiler::compile_workspace_material(compiler, m);
    const std::uint64_t bytes = r->program ? sandpaper::schema::grid_bytes(*r->program) : 0;
    if (kept_.size() >= kMaxKept || held_ + bytes > kMaxHeldBytes) {
      kept_.clear();
      held_ = 0;
    }
    if (bytes <= kMaxHeldBytes) {
      kept_.emplace(std::move(key), r);
      held_ += bytes;
    }
    return r;
  }

 private:
  static constexpr std::size_t kMaxKept = 512;
  static constexpr std::uint64_t kMaxHeldBytes = std::uint64_t{64} << 20;
  std::map<std::pair<std::string, std::string>, std::shared_ptr<const sandpaper::compiler::CompileResult>> kept_;
  std::uint64_t held_ = 0;
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string text(reinterpret_cast<const char*>(data), size);
  // A force-table budget of 32 MiB rather than 512: the refusal (E0535) is then within the search's
  // reach, and a workspace at the budget stays inside libFuzzer's memory limit under ASan.
  static MaterialMemo memo;
  compiler::WorkspaceOptions options;
  options.max_grid_bytes = kGridBudget;
  options.compile_material = [](const compiler::Compiler& c, const compiler::WorkspaceMaterial& m) { return memo.compile(c, m); };
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
