#pragma once
// The compiler's public API: material text -> patch program, with diagnostics.
//
//   sandpaper::compiler::Compiler c({});                 // shipped library and calibration
//   auto r = c.compile_file("corduroy.hmat");
//   if (!r.ok()) std::cerr << format_diagnostics(r.diagnostics);
//   else sandpaper::schema::write_patch_file("corduroy.patch", *r.program);
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/data_dirs.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/library.hpp"
#include "sandpaper/compiler/resolved.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::compiler {

struct CompileOptions {
  std::string device = "sim";               // a device calibration in calibration/devices/
  std::filesystem::path library_dir;        // empty: default_library_dir()
  std::filesystem::path calibration_dir;    // empty: calibration::default_calibration_dir()
  // A layered library, front root first (library.hpp); when set, library_dir is not used. Both
  // empty: default_library_path() ($SANDPAPER_LIBRARY_PATH, else default_library_dir()).
  std::vector<std::filesystem::path> library_path;
};

struct CompileResult {
  Diagnostics diagnostics;
  std::optional<ResolvedMaterial> material;     // set when resolution succeeded
  std::optional<schema::PatchProgram> program;  // set only if there were no errors at all
  bool ok() const { return program.has_value() && !diagnostics.has_errors(); }
};

class Compiler {
 public:
  // Throws calibration::CalibrationError if the calibration data cannot be read, and
  // std::invalid_argument for an unknown device (the message lists the known ones).
  explicit Compiler(CompileOptions options);
  // With a library already read (options' library folders are then not read): for instance the
  // part of a library an incremental index build needs (Library's `only_files` constructor).
  Compiler(CompileOptions options, Library library);
  // Sharing one library read with other compilers (for instance one per device, as `library check`
  // has: each would otherwise hold its own copy of every entry).
  Compiler(CompileOptions options, std::shared_ptr<const Library> library);
  // With the calibration already loaded (options' calibration folder is then not read): for instance
  // through a calibration::ParsedFileCache, by a caller that builds many compilers on one folder.
  Compiler(CompileOptions options, std::shared_ptr<const Library> library, calibration::CalibrationSet calibration);

  // `path` is shown in diagnostics as given. A missing file is a diagnostic, not an exception.
  CompileResult compile_file(const std::filesystem::path& path) const;
  // One-line expressions (`-e`): statements separated by ';', or a bare library name.
  CompileResult compile_text(const std::string& text, const std::string& display_name = "<-e>") const;

  const calibration::CalibrationSet& calibration() const { return calibration_; }
  const calibration::DeviceCalibration& device() const { return *device_; }
  const Library& library() const { return *library_; }
  const CompileOptions& options() const { return options_; }  // as given (empty folders: the defaults)

 private:
  CompileOptions options_;
  calibration::CalibrationSet calibration_;
  const calibration::DeviceCalibration* device_ = nullptr;
  std::shared_ptr<const Library> library_;
};

}  // namespace sandpaper::compiler
