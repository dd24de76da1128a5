// Height-map images read through OpenImageIO (compiler/src/codegen/height_field_image.cpp, `heightmap "x.png"`):
// the bytes as the image file of a material, named with the extension its first bytes ask for (as a
// user names a file; bytes that match no format are read as TGA, which has no magic; only the reader
// the extension names opens the file, docs/RELIABILITY.md F21). The header checks (size, channels,
// bytes before any pixel is allocated), the decoder's error state and the height field built from the pixels must give a program that passes
// the checks of every compiled program (fuzz_compile.hpp), or diagnostics; never a crash, hang or
// an allocation past the stated budget (libFuzzer's -rss_limit_mb; docs/RELIABILITY.md, "Limits").
// OpenImageIO is not instrumented: coverage guides only through Sandpaper's side.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "fuzz_compile.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/compiler/diagnostic.hpp"

namespace {

std::string_view extension_for(std::string_view b) {
  if (b.starts_with("\x89PNG")) return ".png";
  if (b.starts_with("II*") || b.starts_with("MM\0*")) return ".tif";
  if (b.starts_with("v/1\x01")) return ".exr";
  if (b.starts_with("\xff\xd8")) return ".jpg";
  if (b.starts_with("BM")) return ".bmp";
  if (b.size() > 1 && b[0] == 'P' && b[1] >= '1' && b[1] <= '7') return ".pnm";
  if (b.starts_with("#?")) return ".hdr";
  return ".tga";  // no magic of its own: TGA, or a file OpenImageIO must recognise by its content
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto path = fuzz::scratch_dir() / ("heights" + std::string(extension_for(bytes)));
  fuzz::write_file(path, bytes);
  // A byte from the middle picks the options, so that each seed reaches each reading of its file.
  const unsigned pick = size == 0 ? 0u : data[size / 2];
  std::string text = "heightmap \"" + path.string() + "\" size 20 mm";
  if (pick & 1) text += " invert";
  if (pick & 2) text += " repeat";
  if (pick & 4) text += " smoothing 0.5 mm";
  if (pick & 16) text += " channel A";     // the alpha channel (E0403 where there is none)
  if (pick & 32) text += " sampling 1 mm";  // resampled to 20 x 20 through OpenImageIO's resize
  text += (pick & 8) ? "\nroughness 0.5\n" : " amplitude 1 N\n";
  const auto result = fuzz::shipped_compiler().compile_text(text, "<fuzz-image>");
  (void)compiler::format_diagnostics(result.diagnostics);
  if (result.ok()) fuzz::check_compiled_program(*result.program, pick);
  std::error_code ec;
  std::filesystem::remove(path, ec);  // the next input may take another name
  return 0;
}
