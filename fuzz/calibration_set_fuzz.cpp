// A calibration folder as a whole (calibration/: maps, levels, devices, knowledge), as a lab shares
// one: the input's first byte picks one of the shipped files, the rest replaces it in a scratch copy
// of the folder, and a compiler is built on that folder (CalibrationSet::load checks every file and
// how they refer to each other; the unchanged files come parsed from a ParsedFileCache). If it
// loads, two descriptions that reach every kind of file (a roughness level through the levels and
// the compile map, a library entry, the other percepts' maps) are compiled for the device the file
// belongs to, or "sim", and every program is checked as the material target checks one: it reads
// back and plays within the clamp (fuzz_compile.hpp).
// Expected rejections: CalibrationError (the folder), std::invalid_argument (a device file whose
// name no longer matches). Nothing else is caught. The file is put back after each input.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_compile.hpp"
#include "fuzz_support.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/library.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sandpaper;

struct ShippedFile {
  fs::path relative;  // "devices/sim.toml"
  std::string text;
};

// The scratch copy of the shipped folder, and its files in a fixed order (what the first byte picks).
const fs::path& folder() {
  static const fs::path dir = [] {
    const auto d = fuzz::scratch_dir() / "calibration";
    fs::create_directories(d);
    for (const char* sub : {"maps", "levels", "devices", "knowledge"})
      fs::copy(fuzz::source_dir() / "calibration" / sub, d / sub,
               fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    return d;
  }();
  return dir;
}

const std::vector<ShippedFile>& files() {
  static const std::vector<ShippedFile> all = [] {
    std::vector<ShippedFile> out;
    for (const char* sub : {"maps", "levels", "devices", "knowledge"}) {
      std::vector<fs::path> names;
      for (const auto& e : fs::directory_iterator(folder() / sub))
        if (e.path().extension() == ".toml") names.push_back(e.path());
      std::sort(names.begin(), names.end());
      for (const auto& p : names) out.push_back({fs::relative(p, folder()), fuzz::read_file(p)});
    }
    return out;
  }();
  return all;
}

std::shared_ptr<const compiler::Library> library() {
  static const auto lib = std::make_shared<const compiler::Library>(fuzz::source_dir() / "library");
  return lib;
}

// The shipped files, parsed once. Each input changes one file, and only that one is parsed and
// validated again: the other thirteen were 13/14 of every load (perf, 2026-11-25). The cache learns
// the shipped files alone, before the first input, so what an input reaches depends on its bytes
// only, never on the inputs before it.
calibration::ParsedFileCache& shipped_files() {
  static calibration::ParsedFileCache cache;
  static const bool learned = [] {
    (void)calibration::CalibrationSet::load(folder(), &cache);
    cache.set_learning(false);
    return true;
  }();
  (void)learned;
  return cache;
}

void compile_with(const std::string& device, std::uint32_t variant) {
  compiler::CompileOptions o;
  o.device = device;
  o.calibration_dir = folder();
  std::optional<compiler::Compiler> c;
  try {
    c.emplace(o, library(), calibration::CalibrationSet::load(folder(), &shipped_files()));
  } catch (const calibration::CalibrationError&) {
    return;
  } catch (const std::invalid_argument&) {
    return;  // no device of that name (a device file renamed inside)
  }
  // Two compiles, each program played: a valid folder costs 10 ms in the fuzzing build as it is.
  for (const char* text : {"roughness coarse; grating period 2.5 mm; softness 0.4",
                           "like corduroy; viscosity 0.5; slipperiness 0.5"}) {
    const auto result = c->compile_text(text, "<fuzz>");
    (void)compiler::format_diagnostics(result.diagnostics);
    fuzz::dump_json(compiler::compile_json(result, std::nullopt));
    fuzz::check(!result.program || !result.diagnostics.has_errors(), "a compile with errors produced a program");
    if (result.ok()) fuzz::check_compiled_program(*result.program, variant);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const auto& all = files();
  (void)shipped_files();  // before the first input changes a file
  const ShippedFile& target = all[data[0] % all.size()];
  const auto path = folder() / target.relative;
  fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
  // The device whose file this is, by its file name (the name inside must agree, or it is unknown).
  const std::string device = target.relative.parent_path() == "devices" ? target.relative.stem().string() : "sim";
  compile_with(device, static_cast<std::uint32_t>(size));
  fuzz::write_file(path, target.text);
  return 0;
}
