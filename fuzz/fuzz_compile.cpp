#include "fuzz_compile.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_play.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace sandpaper::fuzz {

const compiler::Compiler& shipped_compiler() {
  static const compiler::Compiler c([] {
    compiler::CompileOptions o;
    o.library_dir = source_dir() / "library";
    o.calibration_dir = source_dir() / "calibration";
    return o;
  }());
  return c;
}

namespace {
// The reader must take whatever the writer wrote (issue 16, item 1). False: refused, and the
// "readback" defect is tolerated.
bool reads_back(const std::vector<unsigned char>& bytes, schema::PatchProgram& into, const char* how) {
  try {
    into = schema::deserialize(bytes);
    return true;
  } catch (const schema::PatchFormatError& e) {
    if (known_defect_tolerated("readback")) return false;
    fail(std::string("a compiled program written ") + how + " does not read back: " + e.what());
  }
}
}  // namespace

void check_compiled_program(const schema::PatchProgram& program, std::uint32_t variant) {
  const auto bytes = schema::serialize(program);
  schema::PatchProgram back;
  if (!reads_back(bytes, back, "plain")) return;
  check(schema::serialize(back) == bytes, "write -> read -> write changed a compiled program's bytes");
  schema::PatchWriteOptions compact;
  compact.compact_grids = true;
  schema::PatchProgram compact_back;
  if (!reads_back(schema::serialize(program, compact), compact_back, "compact")) return;
  dump_json(schema::to_json(back));

  try {
    runtime::PatchEvaluator evaluator(back);
    const auto report = play_and_check(evaluator, variant);
    if (report.stop_cause != runtime::StopCause::Completed && !known_defect_tolerated("unplayable"))
      fail(std::string("a compiled program stops the servo loop: ") + runtime::stop_cause_name(report.stop_cause));
  } catch (const std::invalid_argument& e) {
    if (known_defect_tolerated("unplayable")) return;
    fail(std::string("the runtime refuses a compiled program: ") + e.what());
  }
}

}  // namespace sandpaper::fuzz
