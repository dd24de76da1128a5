// Workspace programs (.wsp, what the runtime-only player reads) through
// schema::read_workspace_program_file, which takes only a path: the input is written to one scratch
// file, once as given and once with its header and CRC-32 fixed up so mutations reach the field
// parser. An accepted program is written and read again unchanged, its JSON serialised, and, if
// the runtime accepts it, played for 64 ticks within the clamp.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_play.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/runtime/workspace_evaluator.hpp"
#include "sandpaper/schema/workspace_io.hpp"
#include "sandpaper/schema/workspace_json.hpp"

namespace {

void try_bytes(const std::vector<unsigned char>& bytes, std::uint32_t variant) {
  using namespace sandpaper;
  const auto path = fuzz::scratch_dir() / "input.wsp";
  fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  schema::WorkspaceProgram ws;
  try {
    ws = schema::read_workspace_program_file(path);
  } catch (const schema::PatchFormatError&) {
    return;
  }
  const auto again_path = fuzz::scratch_dir() / "again.wsp";
  schema::write_workspace_program_file(again_path, ws);
  const std::string written = fuzz::read_file(again_path);
  schema::WorkspaceProgram again;
  try {
    again = schema::read_workspace_program_file(again_path);
  } catch (const schema::PatchFormatError& e) {
    fuzz::fail(std::string("a workspace the reader accepted, written again, does not read back: ") + e.what());
  }
  schema::write_workspace_program_file(again_path, again);
  fuzz::check(fuzz::read_file(again_path) == written, "read -> write -> read -> write changed the bytes");
  fuzz::dump_json(schema::to_json(ws));
  try {
    runtime::WorkspaceEvaluator evaluator(ws);
    (void)fuzz::play_and_check(evaluator, variant);
  } catch (const std::invalid_argument&) {
    // Refused by the runtime's checks.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const auto fixed = fuzz::with_valid_header(data, size, "SNDWKSPC", schema::kWorkspaceFormatVersion);
  std::uint32_t variant = 0;
  std::memcpy(&variant, fixed.data() + 24, sizeof variant);
  const std::vector<unsigned char> raw(data, data + size);
  try_bytes(raw, variant);
  if (raw != fixed) try_bytes(fixed, variant);
  return 0;
}
