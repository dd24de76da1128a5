#include "sandpaper/compiler/compiler.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "sandpaper/compiler/codegen.hpp"
#include "sandpaper/compiler/felt_at_speed.hpp"
#include "sandpaper/compiler/knowledge_report.hpp"
#include "sandpaper/compiler/lexer.hpp"
#include "sandpaper/compiler/parser.hpp"
#include "sandpaper/compiler/resolver.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {
namespace {

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
}

// A patch names no absolute path of the machine that compiled it (docs/PATCH_FORMAT.md): a material
// file or an image given by absolute path is named by its file name alone in provenance and warnings.
// Diagnostics on the terminal keep the path as given.
void strip_machine_paths(schema::PatchProgram& program, const SourceFile& file, const ResolvedMaterial& m) {
  std::vector<std::string> absolute;
  if (std::filesystem::path(file.name).is_absolute()) absolute.push_back(file.name);
  if (const auto* h = std::get_if<ResolvedHeightmap>(&m.texture))
    for (const auto& p : {h->stated_path, h->path})
      if (std::filesystem::path(p).is_absolute()) absolute.push_back(p);
  // Longest first, so that a path is not half-replaced by a shorter one inside it.
  std::sort(absolute.begin(), absolute.end(), [](const auto& a, const auto& b) { return a.size() > b.size(); });
  for (const auto& from : absolute) {
    const std::string to = std::filesystem::path(from).filename().string();
    for (auto& pv : program.provenance) {
      replace_all(pv.source, from, to);
      replace_all(pv.stated, from, to);
    }
    for (auto& w : program.warnings) replace_all(w.message, from, to);
    replace_all(program.describes, from, to);
  }
}

CompileResult compile_source(std::shared_ptr<const SourceFile> file, const Library& lib,
                             const calibration::CalibrationSet& cal, const calibration::DeviceCalibration& device) {
  CompileResult r;
  auto tokens = lex(file, r.diagnostics);
  auto syntax = parse(tokens, file, r.diagnostics);
  ResolveContext ctx{lib, cal, {}};
  ResolvedMaterial m = resolve(syntax, ctx, r.diagnostics);
  // Never use the output of a failed phase: stop at the first phase with errors.
  if (r.diagnostics.has_errors()) return r;
  r.material = m;
  schema::PatchProgram program;
  if (!generate(m, cal, device, program, r.diagnostics)) return r;
  warn_roughness_domain(m, cal, r.diagnostics);
  // What the thesis found about textures like this one (Ch. 4): needs the compiled force.
  warn_believability(m, program, cal, r.diagnostics);
  // What a hand moving at a common speed feels of a grating at the device's servo rate (issue 15).
  warn_felt_at_speed(m, program, cal, device, r.diagnostics);
  for (const auto& d : r.diagnostics.all())
    if (d.severity == Severity::Warning) program.warnings.push_back({d.code, d.location.str() + ": " + d.message});
  strip_machine_paths(program, *file, m);
  r.program = std::move(program);
  return r;
}

}  // namespace

Compiler::Compiler(CompileOptions options)
    : options_(std::move(options)),
      calibration_(calibration::CalibrationSet::load(
          options_.calibration_dir.empty() ? calibration::default_calibration_dir() : options_.calibration_dir)),
      library_(options_.library_dir.empty() ? default_library_dir() : options_.library_dir) {
  device_ = calibration_.find_device(options_.device);
  if (!device_) {
    std::string names;
    for (const auto& d : calibration_.devices()) names += (names.empty() ? "" : ", ") + d.name;
    throw std::invalid_argument("unknown device '" + options_.device + "'; known devices: " + names);
  }
  // A device with its own fitted maps (docs/EXPERIMENTS.md) compiles percepts through them.
  calibration_.select_device(device_->name);
}

CompileResult Compiler::compile_file(const std::filesystem::path& path) const {
  std::string text;
  try {
    text = schema::read_input_file(path, schema::limits::kMaxSourceBytes);
  } catch (const schema::InputFileError& e) {
    CompileResult r;
    auto f = std::make_shared<const SourceFile>(path.string(), "");
    r.diagnostics.error("E0001", SourceLocation{f, 0, 0, 1}, std::string("cannot read material file: ") + e.what(),
                        "check the path; material files end in .hmat");
    return r;
  }
  return compile_source(std::make_shared<const SourceFile>(path.string(), std::move(text)), library_, calibration_,
                        *device_);
}

CompileResult Compiler::compile_text(const std::string& text, const std::string& display_name) const {
  return compile_source(std::make_shared<const SourceFile>(display_name, text), library_, calibration_, *device_);
}

}  // namespace sandpaper::compiler
