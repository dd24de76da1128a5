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

// The file's own `accept CODE "reason"` statements turn the warnings of those codes into notes that
// give the reason (metadata: not inherited through `like`, each entry accepts for itself).
void apply_accepts(const MaterialSyntax& syntax, Diagnostics& diagnostics) {
  std::vector<const AcceptStmt*> accepts;
  for (const auto& st : syntax.statements)
    if (const auto* a = std::get_if<AcceptStmt>(&st.node)) accepts.push_back(a);
  if (accepts.empty()) return;
  Diagnostics out;
  for (const auto& d : diagnostics.all()) {
    const auto it = std::find_if(accepts.begin(), accepts.end(), [&](const AcceptStmt* a) { return a->code == d.code; });
    Diagnostic* added = nullptr;
    if (d.severity == Severity::Warning && it != accepts.end()) {
      added = &out.accepted(schema::Code::of(d.code), d.location, "accepted: " + d.message, d.suggestion);
      added->notes = d.notes;
      added->notes.push_back({(*it)->location, "accepted here: \"" + (*it)->reason + "\""});
      continue;
    }
    if (d.code == "E0009" || d.code == "W0009") continue;  // recounted by append below
    added = d.severity == Severity::Error     ? &out.error(schema::Code::of(d.code), d.location, d.message, d.suggestion)
            : d.severity == Severity::Warning ? &out.warning(schema::Code::of(d.code), d.location, d.message, d.suggestion)
                                              : &out.accepted(schema::Code::of(d.code), d.location, d.message, d.suggestion);
    added->notes = d.notes;
  }
  diagnostics = std::move(out);
}

CompileResult compile_phases(const MaterialSyntax& syntax, const Library& lib,
                             const calibration::CalibrationSet& cal, const calibration::DeviceCalibration& device,
                             CompileResult r) {
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
  // What a hand moving at a common speed feels of a grating at the device's servo rate.
  warn_felt_at_speed(m, program, cal, device, r.diagnostics);
  apply_accepts(syntax, r.diagnostics);
  for (const auto& d : r.diagnostics.all())
    if (d.severity == Severity::Warning) program.warnings.push_back({d.code, d.location.str() + ": " + d.message});
  r.program = std::move(program);
  return r;
}

CompileResult compile_source(std::shared_ptr<const SourceFile> file, const Library& lib,
                             const calibration::CalibrationSet& cal, const calibration::DeviceCalibration& device) {
  CompileResult r;
  auto tokens = lex(file, r.diagnostics);
  auto syntax = parse(tokens, file, r.diagnostics);
  r = compile_phases(syntax, lib, cal, device, std::move(r));
  if (!r.program) apply_accepts(syntax, r.diagnostics);  // a failed compile's warnings are accepted too
  return r;
}

}  // namespace

Compiler::Compiler(CompileOptions options)
    : Compiler(options, Library(!options.library_path.empty()  ? options.library_path
                                : !options.library_dir.empty() ? std::vector<std::filesystem::path>{options.library_dir}
                                                                : default_library_path())) {}

Compiler::Compiler(CompileOptions options, Library library)
    : Compiler(std::move(options), std::make_shared<const Library>(std::move(library))) {}

Compiler::Compiler(CompileOptions options, std::shared_ptr<const Library> library)
    : Compiler(options, std::move(library),
               calibration::CalibrationSet::load(options.calibration_dir.empty() ? calibration::default_calibration_dir()
                                                                                 : options.calibration_dir)) {}

Compiler::Compiler(CompileOptions options, std::shared_ptr<const Library> library, calibration::CalibrationSet calibration)
    : options_(std::move(options)), calibration_(std::move(calibration)), library_(std::move(library)) {
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
    r.diagnostics.error("E0001", SourceLocation{f, 0, 0, 1}, "cannot open material file '" + path.string() + "': " + e.reason,
                        "check the path; material files end in .hmat");
    return r;
  }
  return compile_source(std::make_shared<const SourceFile>(path.string(), std::move(text)), *library_, calibration_,
                        *device_);
}

CompileResult Compiler::compile_text(const std::string& text, const std::string& display_name) const {
  return compile_source(std::make_shared<const SourceFile>(display_name, text), *library_, calibration_, *device_);
}

}  // namespace sandpaper::compiler
