// Sandpaper array files (.depth, .shade; schema/array_file.hpp): decode_array, which must give back
// the very bytes through encode_array; then, as a user would use one, the file as a material's
// height map (`heightmap "x.depth" size 20 mm`) through the compiler, whose program must pass the
// checks of every compiled program (fuzz_compile.hpp). Expected rejection: schema::ArrayFileError.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_compile.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/schema/array_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::vector<unsigned char> bytes(data, data + size);
  schema::ArrayFile array;
  try {
    array = schema::decode_array(bytes, "<fuzz>.depth");
  } catch (const schema::ArrayFileError&) {
    return 0;
  }
  fuzz::check(array.values.size() == std::size_t{array.width} * array.height, "decoded values != width x height");
  fuzz::check(schema::encode_array(array) == bytes, "decode -> encode changed the bytes");

  const auto path = fuzz::scratch_dir() / "heights.depth";
  fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
  // The low bits of the first value pick the options, so the corpus reaches each reading of the file.
  const unsigned pick = array.values.empty() ? 0u : array.values[0];
  std::string text = "heightmap \"" + path.string() + "\" size 20 mm";
  if (pick & 1) text += " invert";
  if (pick & 2) text += " repeat";
  if (pick & 4) text += " smoothing 0.5 mm";
  text += (pick & 8) ? "\nroughness 0.5\n" : " amplitude 1 N\n";
  const auto result = fuzz::shipped_compiler().compile_text(text, "<fuzz-array>");
  (void)compiler::format_diagnostics(result.diagnostics);
  if (result.ok()) fuzz::check_compiled_program(*result.program, pick);
  return 0;
}
