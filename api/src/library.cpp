// sandpaper::Library: the compiler with the shipped (or given) library and calibration, and the
// two questions applications ask of it: a material by name, a roughness level by name.
#include <cstdlib>
#include <system_error>

#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/data_dirs.hpp"
#include "sandpaper/sandpaper.hpp"

namespace sandpaper {
namespace {

// A missing data directory would otherwise show up later as "unknown material" or a list of
// unreadable calibration files; name every missing one at once, with what chose it (in words a C or
// Python caller knows too: no C++ names).
compiler::DataDirChoice given_or_found(const std::filesystem::path& given, compiler::DataDirChoice found) {
  return given.empty() ? found : compiler::DataDirChoice{given, "the caller: the folder given when opening the library"};
}

}  // namespace

struct Library::Impl {
  std::filesystem::path library_dir, calibration_dir;
  std::unique_ptr<compiler::Compiler> compiler;
};

Library::Library() : Library(LibraryOptions{}) {}

Library::Library(const std::filesystem::path& library_dir)
    : Library(LibraryOptions{.library_dir = library_dir, .calibration_dir = {}, .device = "sim", .library_path = {}}) {}

Library::Library(LibraryOptions options) : impl_(std::make_unique<Impl>()) {
  if (options.library_path.empty() && options.library_dir.empty())
    if (const char* env = std::getenv("SANDPAPER_LIBRARY_PATH"); env && *env) options.library_path = compiler::default_library_path();
  std::vector<std::pair<std::string, compiler::DataDirChoice>> dirs;
  for (const auto& root : options.library_path) dirs.push_back({"library", compiler::DataDirChoice{root, "the library path"}});
  if (!options.library_path.empty()) options.library_dir = options.library_path.front();
  auto library = given_or_found(options.library_dir, compiler::find_library_dir());
  auto calibration = given_or_found(options.calibration_dir, compiler::find_calibration_dir());
  if (dirs.empty()) dirs.push_back({"library", library});
  dirs.push_back({"calibration", calibration});
  if (auto missing = compiler::missing_data_dirs_message(dirs);
      !missing.empty())
    throw Error(missing);
  impl_->library_dir = std::move(library.dir);
  impl_->calibration_dir = std::move(calibration.dir);
  try {
    impl_->compiler = std::make_unique<compiler::Compiler>(
        compiler::CompileOptions{options.device, impl_->library_dir, impl_->calibration_dir, options.library_path});
  } catch (const calibration::CalibrationError& e) {
    throw Error(e.what());
  } catch (const std::invalid_argument& e) {  // unknown device: the message lists the known ones
    throw Error(e.what());
  }
}

Library::~Library() = default;
Library::Library(Library&&) noexcept = default;
Library& Library::operator=(Library&&) noexcept = default;

Material Library::compile(const std::string& name_or_statements) const {
  compiler::CompileResult result = impl_->compiler->compile_text(name_or_statements, "<compile>");
  if (!result.ok()) throw CompileError(std::move(result.diagnostics));
  return Material(std::move(*result.program));
}

Material Library::roughness_level(const std::string& level) const { return this->level("roughness", level); }

Material Library::level(const std::string& percept, const std::string& level) const {
  level_value(percept, level);  // refuse unknown names (and anything that is not a bare name) here
  return compile(percept + " " + level);
}

const compiler::Compiler& Library::compiler() const noexcept { return *impl_->compiler; }

std::vector<std::string> Library::names() const { return impl_->compiler->library().names(); }

std::vector<std::string> Library::roughness_levels() const { return levels("roughness"); }

double Library::roughness_level_value(const std::string& level) const { return level_value("roughness", level); }

std::vector<std::string> Library::levels(const std::string& percept) const {
  std::vector<std::string> out;
  for (const auto* l : impl_->compiler->calibration().levels(percept)) out.push_back(l->name);
  return out;
}

double Library::level_value(const std::string& percept, const std::string& level) const {
  for (const auto* l : impl_->compiler->calibration().levels(percept))
    if (l->name == level) return l->value;
  throw UnknownLevel(level, levels(percept), percept, percepts_with_levels(impl_->compiler->calibration()));
}

const std::filesystem::path& Library::library_dir() const noexcept { return impl_->library_dir; }
const std::filesystem::path& Library::calibration_dir() const noexcept { return impl_->calibration_dir; }

}  // namespace sandpaper
