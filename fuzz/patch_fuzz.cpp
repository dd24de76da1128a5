// Patch programs (.patch) through the reader, schema::deserialize: once as given (so header checks
// run) and once with the header and CRC-32 fixed up (fuzz_support.hpp), so mutations reach the
// field parser. Every program the reader accepts must be written back and read again unchanged,
// its JSON view must serialise, and, if the runtime accepts it (PatchEvaluator throws
// std::invalid_argument for a program it refuses), it is played for 64 ticks with every
// commanded force finite and within the device's maximum: the runtime's safety must hold for any
// program that reads, not just the ones the compiler makes.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "fuzz_play.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/patch_json.hpp"

namespace {

void check_program(const sandpaper::schema::PatchProgram& program, std::uint32_t variant) {
  using namespace sandpaper;
  const auto bytes = schema::serialize(program);
  schema::PatchProgram again;
  try {
    again = schema::deserialize(bytes);
  } catch (const schema::PatchFormatError& e) {
    fuzz::fail(std::string("a program the reader accepted, written again, does not read back: ") + e.what());
  }
  fuzz::check(schema::serialize(again) == bytes, "read -> write -> read -> write changed the bytes");
  fuzz::dump_json(schema::to_json(program));
  try {
    runtime::PatchEvaluator evaluator(program);
    (void)fuzz::play_and_check(evaluator, variant);
  } catch (const std::invalid_argument&) {
    // Refused by the runtime's checks: what it promises for a program it cannot play.
  }
}

// Returns whether `bytes` read as a program (then checked).
bool try_bytes(const std::vector<unsigned char>& bytes, std::uint32_t variant) {
  sandpaper::schema::PatchProgram program;
  try {
    program = sandpaper::schema::deserialize(bytes);
  } catch (const sandpaper::schema::PatchFormatError&) {
    return false;
  }
  check_program(program, variant);
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::vector<unsigned char> raw(data, data + size);
  const auto fixed = fuzz::with_valid_header(data, size, "SNDPATCH", schema::kPatchFormatVersion);
  std::uint32_t variant = 0;
  std::memcpy(&variant, fixed.data() + 24, sizeof variant);  // the CRC: a cheap hash of the payload
  const bool raw_read = try_bytes(raw, variant);
  if (!(raw_read && raw == fixed)) try_bytes(fixed, variant);
  return 0;
}
