#pragma once
// The `sandpaper` command line: one command a file (cmd_<name>.cpp), registered and dispatched in main.cpp;
// `sandpaper --help` lists them. Exit codes: 0 success, 1 the input is wrong (diagnostics printed), 2 usage or
// environment errors, 3 internal errors.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "sandpaper/player/exit_codes.hpp"
#include "sandpaper/player/play_workspace.hpp"
#include "sandpaper/player/safety_guards.hpp"
#include "sandpaper/compiler/gltf_import.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/runtime/device.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/servo_loop.hpp"
#include "sandpaper/schema/patch_program.hpp"

namespace sandpaper::cli {


struct CommonOptions {
  std::string file;        // material file or patch program
  std::string expression;  // -e text
  std::string device = "sim";
  bool device_given = false;  // --device was on the command line (run chooses a device otherwise)
  std::string library_dir;
  std::string calibration_dir;
  bool json = false;
  bool compact = false;    // compile: height-field grids as binary16 where forces stay within 0.1 %
  double position_rate_hz = 0;   // explain: how often new positions reach the servo, Hz (0: the servo rate)
  double command_rate_hz = 0;    // explain: how often new commands reach the device per axis, Hz (0: its bus interval)
  double design_speed_mm_s = 0;  // explain: the hand speed the material is designed for, mm/s (0: none)
};

// What a material or patch input turned into. For .patch inputs `compile` is empty.
struct LoadedInput {
  std::optional<compiler::CompileResult> compile;
  schema::PatchProgram program;
};

compiler::Compiler make_compiler(const CommonOptions& o);
// The device calibrations --calibration selects (or the default folder); CalibrationError when unreadable.
calibration::CalibrationSet load_calibration_set(const CommonOptions& o);
// Compiles the file or expression (or reads a .patch); prints diagnostics to stderr. Returns
// nullopt (after printing) when the input has errors.
std::optional<LoadedInput> load_input(const CommonOptions& o, const compiler::Compiler& c, bool allow_patch);
using compiler::diagnostics_json;  // compiler/compile_json.hpp
// The simulated device's limits from the compiler's device calibration (calibration/devices/<name>.toml).
runtime::DeviceLimits limits_of(const compiler::Compiler& c);

int cmd_compile(const CommonOptions& o, const std::string& output, bool explain);
// `compile --dump STAGE` (cmd_dump.cpp): tokens, syntax, resolved or patch, printed on stdout.
int cmd_dump(const CommonOptions& o, const std::string& stage);
// `sandpaper compile A.hmat B.hmat FOLDER/ -o OUT/`: every material (a folder's .hmat files, found
// recursively, keep their place below it) compiled in this one process into OUT. Exit 1 if any
// failed (those write nothing), 2 for unusable arguments (nothing is compiled).
int cmd_compile_batch(const CommonOptions& o, const std::vector<std::string>& inputs, const std::string& out_dir);
struct PlayRequest;  // player/include/sandpaper/player/play_patch.hpp
int cmd_run(const CommonOptions& o, PlayRequest r, bool watch = false);
// Replaces this process with `sandpaper-play` (beside this executable) given argv[2..] (what
// followed `run`); returns -1, after a note, when it cannot, and the caller plays in-process.
int exec_player(int argc, char** argv);
int cmd_inspect(const std::string& file, bool json, bool tables);
// What `inspect` prints of a program, below its heading: name, device, size, force, terms, provenance.
void print_patch_program(const schema::PatchProgram& p);
// USB HID PID joysticks plugged in (cmd_devices.cpp, docs/USB_PID.md).
int cmd_devices(const CommonOptions& o);
// `sandpaper devices --udev-rules`: the udev rules file for the devices the calibration files name.
int cmd_devices_udev_rules(const CommonOptions& o);
int cmd_library(const CommonOptions& o);
// Opens the device `spec` names through the device factory (runtime/devices/open_device.hpp) with
// the calibration `o` selects; nullopt after printing "sandpaper COMMAND: why" (and the udev help).
std::optional<runtime::OpenedDevice> open_device_for(const CommonOptions& o, runtime::DeviceSpec spec,
                                                     const std::string& command);
// `sandpaper studio` (cmd_studio.cpp, docs/STUDIO.md): `path` a material, a workspace or a folder.
struct StudioOptions {
  std::string path = ".";
  std::string listen = "127.0.0.1:4780";
  bool listen_given = false;
  double rate_hz = 1000;
  SafetyGuards guards;
  bool uncalibrated = false;  // --uncalibrated: an evdev device no calibration file names may play
};
int cmd_studio(const CommonOptions& o, const StudioOptions& so);

// Workspaces (.hws, thesis Appendix B): WorkspaceRunOptions and the playing are in player/include/sandpaper/player/play_workspace.hpp.
// True when the input is a workspace file rather than a material.
inline bool is_workspace_input(const CommonOptions& o) {
  return o.expression.empty() && std::filesystem::path(o.file).extension() == ".hws";
}
int cmd_workspace_compile(const CommonOptions& o, const std::string& output, bool explain);
int cmd_workspace_run(const CommonOptions& o, const WorkspaceRunOptions& ro);

// Movies and shuffles (thesis Appendix B).
struct MovieShuffleOptions {
  std::string movie;
  std::uint64_t seed = 0;
  std::string output;       // empty: <movie stem>-<YYYYMMDD>-<HHMMSS>.shuffle beside the movie
  std::string date, time;   // empty: the system clock's
};
int cmd_movie_shuffle(const MovieShuffleOptions& m, bool json);
int cmd_movie_show(const std::string& file, bool json);
// `sandpaper array`: lengths as text with units ("80mm", "80x60mm", "0.37mm"); empty = not given.
struct ArrayOptions {
  std::string image, size, sampling, channel, depth, output, shade;
  bool invert = false;
};
int cmd_array(const ArrayOptions& o);
// `sandpaper preview`: height.png, field.png, scan.svg and preview.json in `out_dir`, pictures at most
// `side` pixels on their longer side (cmd_preview.cpp; docs/STUDIO.md).
int cmd_preview(const CommonOptions& o, const std::string& out_dir, int side);
// `sandpaper export FILE --format gltf -o OUT.gltf` (cmd_export.cpp, docs/GLTF.md): a material or
// workspace as glTF 2.0 with MPEG_haptic_material. `sandpaper compile ASSET.gltf` reads one back
// (cmd_import.cpp): a .patch, or a workspace program.
int cmd_export(const CommonOptions& o, const std::string& format, const std::string& output);
int cmd_compile_gltf(const CommonOptions& o, const std::string& output);
// `sandpaper explain ASSET.gltf|.glb`: what the asset holds, read back for the device: each patch's
// program (as `inspect` shows it) and place; the material's layers are not in an asset.
int cmd_explain_gltf(const CommonOptions& o);
inline bool is_gltf_input(const CommonOptions& o) { return o.expression.empty() && compiler::is_gltf_path(o.file); }
// 3-D scenes (cmd_scene.cpp, docs/SHAPES.md): a scene file (.hsc), or a glTF asset that is not one
// `sandpaper export` wrote (docs/GLTF.md: those are patches and workspaces, read by cmd_import.cpp).
bool is_scene_input(const CommonOptions& o);
// `sandpaper explain SCENE`: every object, its surfaces, their contact and where each value came
// from, and how each material's layers resolved. `compile SCENE -o OUT.sp3`: the scene program.
int cmd_scene_explain(const CommonOptions& o);
int cmd_scene_compile(const CommonOptions& o, const std::string& output);
// `sandpaper preview SCENE -o DIR`: scene.png (scenes/scene_preview.hpp) and preview.json.
int cmd_scene_preview(const CommonOptions& o, const std::string& out_dir, int side);
// `sandpaper run SCENE --device sim3d` (cmd_scene_run.cpp): the simulated hand strokes each object;
// exit 1 when the run gains energy or is unstable.
int cmd_scene_run(const CommonOptions& o, const PlayRequest& r);
// `sandpaper probe SCENE --from X,Y,Z --to X,Y,Z --steps N`: the device point moved along a segment
// (mm, the scene's frame), the proxy settled at each step, the force (N) printed at each.
struct ProbeOptions {
  std::string from, to;  // "X,Y,Z" in mm
  int steps = 10;
};
int cmd_probe(const CommonOptions& o, const ProbeOptions& p);
// `sandpaper lsp`: the language server on stdin/stdout (editors/lsp, docs/EDITORS.md) until the
// client's `exit`; 0 after a clean shutdown, 1 otherwise.
int cmd_lsp(const CommonOptions& o);
// `sandpaper diagnostics`: the table of diagnostic codes (schema/diagnostic_codes.hpp) as text,
// markdown (what schema/LANGUAGE.md holds) or JSON.
int cmd_diagnostics(bool markdown, bool json);

}  // namespace sandpaper::cli

// `sandpaper calibrate fit|device`: psychophysical maps and device files fitted from
// measurements (cmd_calibrate.cpp; docs/CALIBRATION.md, "Fitting").
namespace CLI {
class App;
}
namespace sandpaper::cli {
struct CalibrateOptions {
  std::string input;             // responses.csv or readings.csv
  std::string output;            // map or device file to write; empty: report only
  std::string percept = "roughness", id;   // fit
  std::string name, base, date;  // device
  bool json = false;
  CLI::App* fit = nullptr;       // set by add_calibrate_command
  CLI::App* device = nullptr;
};
// Registers `calibrate` with its two subcommands on `app`; options land in `o`.
void add_calibrate_command(CLI::App& app, CalibrateOptions& o);
// Runs whichever subcommand was parsed; -1 if neither was. Exit codes as above.
int cmd_calibrate(const CalibrateOptions& o);
// `sandpaper library catalog -o DIR` (cmd_library_catalog.cpp, docs/CATALOG.md): registers it under
// `library`; runs it with the `library` group's options `o` filling what catalog's own leave unset.
// The files of a `--changed` option, "-" replaced by stdin's lines (cmd_library.cpp).
std::vector<std::filesystem::path> changed_files(const std::vector<std::string>& listed);
CLI::App* add_library_catalog_command(CLI::App& library);
int cmd_library_catalog(const CommonOptions& o);

// `sandpaper experiment run|resume|analyse` (cmd_experiment.cpp, docs/EXPERIMENTS.md).
struct ExperimentOptions {
  CommonOptions common;            // --library, --calibration, --json
  std::string target;              // run: the design; resume and analyse: the results folder
  std::string subject, output;     // run
  std::string device = "sim";      // sim, usb, hidraw[:PATH] or evdev[:PATH]
  std::string observer;            // terminal, page or simulated:...; empty: terminal (run), the recorded one (resume)
  bool switch_observer = false;    // resume: answer with --observer, not the recorded observer
  std::string listen = "127.0.0.1:4781";  // --observer page
  bool virtual_clock = false;
  bool uncalibrated = false;       // run: an evdev device no calibration file names may play
  std::string map_out, map_id, pictures;  // analyse
  std::string map_domain = "levels";       // analyse --map-domain: levels | stimuli
  bool allow_mixed_designs = false;
  bool include_incomplete = false; // analyse: pool subjects who did not answer every trial
  SafetyGuards guards;             // run: the live loop's safety stops
  CLI::App* run = nullptr;
  CLI::App* resume = nullptr;
  CLI::App* analyse = nullptr;
};
void add_experiment_command(CLI::App& app, ExperimentOptions& o);
// Runs whichever subcommand was parsed; -1 if none was.
int cmd_experiment(const ExperimentOptions& o);
}  // namespace sandpaper::cli
