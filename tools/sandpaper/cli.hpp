#pragma once
// The `sandpaper` command line: compile, explain, run, inspect, library, array. Exit codes: 0 success,
// 1 the input is wrong (diagnostics printed), 2 usage or environment errors, 3 internal errors.
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUsage = 2;

struct CommonOptions {
  std::string file;        // material file or patch program
  std::string expression;  // -e text
  std::string device = "sim";
  std::string library_dir;
  std::string calibration_dir;
  bool json = false;
};

// What a material or patch input turned into. For .patch inputs `compile` is empty.
struct LoadedInput {
  std::optional<compiler::CompileResult> compile;
  schema::PatchProgram program;
};

compiler::Compiler make_compiler(const CommonOptions& o);
// Compiles the file or expression (or reads a .patch); prints diagnostics to stderr. Returns
// nullopt (after printing) when the input has errors.
std::optional<LoadedInput> load_input(const CommonOptions& o, const compiler::Compiler& c, bool allow_patch);
nlohmann::json diagnostics_json(const compiler::Diagnostics& d);

int cmd_compile(const CommonOptions& o, const std::string& output, bool explain);
int cmd_run(const CommonOptions& o, double rate_hz, double duration_s, const std::string& hand, double speed_mm_s,
            double amplitude_mm, const std::string& trace, bool virtual_clock);
int cmd_inspect(const std::string& file, bool json, bool tables);
int cmd_library(const CommonOptions& o);

// `sandpaper array`: lengths as text with units ("80mm", "80x60mm", "0.37mm"); empty = not given.
struct ArrayOptions {
  std::string image, size, sampling, channel, depth, output, shade;
  bool invert = false;
};
int cmd_array(const ArrayOptions& o);

}  // namespace sandpaper::cli
