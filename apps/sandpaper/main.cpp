// sandpaper: compile, explain, run and inspect haptic materials; write Sandpaper's array files.
// `sandpaper --help` lists the commands; schema/LANGUAGE.md describes material files.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <new>
#include <string_view>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#if SANDPAPER_WITH_CURATION
#include "cmd_library.hpp"
#endif
#include "subsystems.hpp"
#include "sandpaper/player/play.hpp"
#include "sandpaper/player/play_patch.hpp"
#include "sandpaper/calibration/calibration.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/patch_io.hpp"
#include "sandpaper/schema/workspace_io.hpp"
#if SANDPAPER_WITH_SHAPES
#include "sandpaper/shapes/scene_io.hpp"
#endif

namespace {

void add_common(CLI::App* sub, sandpaper::cli::CommonOptions& o, bool input) {
  if (input) {
    sub->add_option("file", o.file, "material file (.hmat) or workspace (.hws)");
    sub->add_option("-e,--expression", o.expression, "material as one line: statements separated by ';', or a library name");
  }
  sub->add_option("--device", o.device, "device calibration to compile for (calibration/devices/); run also takes usb (the first HID PID joystick found, through libusb) hidraw or hidraw:PATH (through the kernel's hidraw node, its driver left bound) and evdev or evdev:PATH (the kernel's own force feedback through the input event node)")->capture_default_str();
  sub->add_option("--library", o.library_dir, "library folder, or folders front first as LAB:WORLD (default: $SANDPAPER_LIBRARY_PATH, $SANDPAPER_LIBRARY, $SANDPAPER_DATA_DIR/library, or the shipped library)");
  sub->add_option("--calibration", o.calibration_dir, "calibration folder (default: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, or the shipped calibration)");
  sub->add_flag("--json", o.json, "print one JSON object instead of text");
}

// A finite number above 0: CLI::PositiveNumber lets NaN and infinity through, and a negative
// number's message names no unit.
CLI::Validator finite_positive(const std::string& what) {
  return CLI::Validator(
      [what](std::string& text) -> std::string {
        double v = 0;
        if (CLI::detail::lexical_cast(text, v) && std::isfinite(v) && v > 0) return {};
        return "must be " + what + ", not " + text;
      },
      "> 0");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace sandpaper::cli;
  // Before anything slow (parsing, loading the library, compiling): a Ctrl-C from here on is a stop request.
  if (argc > 1 && std::string_view(argv[1]) == "run") install_run_stop_handlers();
  CLI::App app{"Sandpaper: compile perceptual material descriptions into patch programs and play them on a force-feedback joystick"};
  app.require_subcommand(1);
  CommonOptions o;
  std::string output;
  bool tables = false;

  auto* compile = app.add_subcommand("compile", "compile a material into a patch program (or many: files and folders, -o FOLDER)");
  std::vector<std::string> compile_inputs;
  compile->add_option("file", compile_inputs, "material file (.hmat) or workspace (.hws); several files or folders compile in one process");
  compile->add_option("-e,--expression", o.expression, "material as one line: statements separated by ';', or a library name");
  add_common(compile, o, false);
  compile->add_option("-o,--output", output, "patch program to write (default: the input with .patch); a folder for several inputs");
  std::string dump_stage;
  compile->add_option("--dump", dump_stage,
                      "print what one compiler phase made of a material instead of writing it: tokens, syntax, the "
                      "resolved material, or the patch program as JSON (tests/golden/stages/ holds them for the examples)")
      ->check(CLI::IsMember({"tokens", "syntax", "resolved", "patch"}));
  compile->add_flag("--compact", o.compact,
                    "store height-field grids as 16-bit floats where every force stays within 0.1 % of the grid's largest (half the file)");
  auto* explain = app.add_subcommand("explain", "show how each layer of a material resolved, with units and sources");
  add_common(explain, o, true);
  explain->add_option("--design-speed", o.design_speed_mm_s,
                      "hand speed the material is designed for, mm/s: a grating's remedies (faster servo, smoothing) "
                      "are measured at it (docs/TEXTURES.md, \"The force a hand really feels\")")
      ->check(finite_positive("a finite hand speed above 0 mm/s"));
  explain->add_option("--position-rate", o.position_rate_hz,
                      "how often new handle positions reach the servo, Hz, when slower than the servo (a loaded bus): "
                      "the device's output at speed is read at it")
      ->check(CLI::Range(1.0, 100000.0));
  explain->add_option("--command-rate", o.command_rate_hz,
                      "how often new force commands reach the device per axis, Hz (default: one per bus interval, the "
                      "device file's [usb] out_interval, shared by the axes a grating drives): the device's output at "
                      "speed is read at it")
      ->check(CLI::Range(1.0, 100000.0));
  auto* run = app.add_subcommand("run", "play a material or patch program on a device");
  add_common(run, o, true);
  PlayRequest play_request;
  add_play_options(run, play_request);
  bool watch = false;
  run->add_flag("--watch", watch, "recompile the file whenever it is saved and swap it in while playing (until Ctrl-C unless --duration)");
  auto* inspect = app.add_subcommand("inspect", "print a patch program");
  std::string patch_file;
  inspect->add_option("file", patch_file, "patch program (.patch)")->required();
  inspect->add_flag("--json", o.json, "print JSON");
  inspect->add_flag("--tables", tables, "include the force tables (with --json)");
  double crossfade_ms = 2;
  run->add_option("--crossfade", crossfade_ms, "workspaces: crossfade time at patch edges, ms")->capture_default_str();
#if SANDPAPER_WITH_CURATION
  auto* library = app.add_subcommand("library", "list the library's entries (no subcommand), or check, index, search, show, near");
  add_common(library, o, false);
  LibraryCommandOptions library_opts;
  add_library_commands(*library, library_opts);
  auto* library_catalog = add_library_catalog_command(*library);
#else
  add_unbuilt_command(app, "library", kCuration);
#endif
  auto* movie = app.add_subcommand("movie", "movie files (lists of workspaces) and their shuffles (thesis Appendix B)");
  movie->require_subcommand(1);
  MovieShuffleOptions shuffle_opts;
  auto* shuffle = movie->add_subcommand("shuffle", "write a shuffle file: the movie's frames in a seeded random order");
  shuffle->add_option("movie", shuffle_opts.movie, "movie file")->required();
  shuffle->add_option("--seed", shuffle_opts.seed, "random seed; the same seed gives the same order everywhere")->required();
  shuffle->add_option("-o,--output", shuffle_opts.output, "shuffle file to write (default: <movie>-<YYYYMMDD>-<HHMMSS>.shuffle beside the movie)");
  shuffle->add_option("--date", shuffle_opts.date, "date to record, YYYY-MM-DD (default: today)");
  shuffle->add_option("--time", shuffle_opts.time, "time to record, HH:MM:SS (default: now)");
  shuffle->add_flag("--json", o.json, "print JSON");
  std::string show_file;
  auto* show = movie->add_subcommand("show", "list a movie's frames, or a shuffle's (checked against its movie)");
  show->add_option("file", show_file, "movie or shuffle file")->required();
  show->add_flag("--json", o.json, "print JSON");

  auto* array = app.add_subcommand("array", "write Sandpaper's array files: an image's 8-bit heights (.depth) and a shaded picture (.shade)");
  ArrayOptions ao;
  array->add_option("image", ao.image, "picture to read as heights (any format OpenImageIO reads, or a .depth file)")->required();
  array->add_option("--size", ao.size, "physical size W[xH] with a unit, e.g. 80mm or 80x60mm")->required();
  array->add_option("--sampling", ao.sampling, "spacing of the array's items, e.g. 0.37mm (default: one per pixel)");
  array->add_option("--channel", ao.channel, "read this channel as the height (default: the luminance rule)");
  array->add_flag("--invert", ao.invert, "dark = high");
  array->add_option("--depth", ao.depth, "relief for the shading, e.g. 0.5mm (default: steepest slope 45 deg)");
  array->add_option("-o,--output", ao.output, "height array to write (.depth)")->required();
  array->add_option("--shade", ao.shade, "also write the shaded picture, lit from the upper left (.shade)");

  auto* devices = app.add_subcommand("devices", "list the USB force-feedback (HID PID) joysticks present");
  devices->add_option("--calibration", o.calibration_dir, "calibration folder (default: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, or the shipped calibration)");
  bool udev_rules = false;
  devices->add_flag("--udev-rules", udev_rules, "print the udev rules that let the logged-in user play, without root, every device the calibration files name (the package installs them as /usr/lib/udev/rules.d/70-sandpaper.rules)");

#if SANDPAPER_WITH_CURATION
  auto* preview = app.add_subcommand("preview", "write a material's preview pictures: shaded height field, force field, force along a scan line");
  add_common(preview, o, true);
  std::string preview_dir;
  int preview_side = 512;
  preview->add_option("-o,--output", preview_dir, "folder to write height.png, field.png, scan.svg and preview.json into")->required();
  preview->add_option("--side", preview_side, "longer side of the pictures, pixels")->capture_default_str();
#else
  add_unbuilt_command(app, "preview", kCuration);
#endif

#if SANDPAPER_WITH_GLTF
  auto* export_cmd = app.add_subcommand("export", "write a material or workspace as a glTF 2.0 asset with the MPEG_haptic_material extension (docs/GLTF.md)");
  add_common(export_cmd, o, true);
  std::string export_format, export_output;
  export_cmd->add_option("--format", export_format, "gltf (glTF 2.0: -o FILE.gltf, one self-contained JSON file; -o FILE.glb, binary) or glb (binary glTF, -o FILE.glb)")->required();
  export_cmd->add_option("-o,--output", export_output, "file to write, e.g. out.gltf")->required();
#else
  add_unbuilt_command(app, "export", kGltf);
#endif

#if SANDPAPER_WITH_SHAPES
  auto* probe = app.add_subcommand("probe", "move the device point along a segment through a 3-D scene and print the force at each step (docs/SHAPES.md)");
  add_common(probe, o, true);
  ProbeOptions probe_opts;
  probe->add_option("--from", probe_opts.from, "start of the segment, X,Y,Z in mm (the scene's frame: x right, y up, z toward the user)")->required();
  probe->add_option("--to", probe_opts.to, "end of the segment, X,Y,Z in mm")->required();
  probe->add_option("--steps", probe_opts.steps, "steps along the segment (the force is printed at steps + 1 points)")->capture_default_str();
#else
  add_unbuilt_command(app, "probe", kShapes);
#endif

#if SANDPAPER_WITH_STUDIO
  auto* studio = app.add_subcommand("studio", "serve Sandpaper Studio: edit, see and feel a material while it plays (docs/STUDIO.md)");
  StudioOptions studio_opts;
  studio->add_option("path", studio_opts.path, "a material (.hmat), a workspace (.hws) or a folder; the studio works inside its folder")->capture_default_str();
  studio->add_option("--device", o.device, "sim (Dummy mode: the mouse moves the hand), usb (the first HID PID joystick, through libusb), hidraw[:PATH] (through its hidraw node, the kernel's driver left bound) or evdev[:PATH] (the kernel's own force feedback through the input event node; docs/DEVICES.md)")->capture_default_str();
  studio->add_option("--listen", studio_opts.listen, "ADDR:PORT to serve on (port 0: any free port); a non-loopback address is warned about")->capture_default_str();
  studio->add_option("--rate", studio_opts.rate_hz, "servo rate, Hz")->capture_default_str();
  studio->add_flag("--uncalibrated", studio_opts.uncalibrated,
                   "with --device evdev[:PATH]: play a force-feedback input device no calibration file names, with the "
                   "uncalibrated-evdev profile (at most a quarter of its strongest force; docs/DEVICES.md)");
  add_guard_options(studio, studio_opts.guards);
  studio->add_option("--library", o.library_dir, "library folder, or folders front first as LAB:WORLD (default: $SANDPAPER_LIBRARY_PATH, $SANDPAPER_LIBRARY, $SANDPAPER_DATA_DIR/library, or the shipped library)");
  studio->add_option("--calibration", o.calibration_dir, "calibration folder (default: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, or the shipped calibration)");
#else
  add_unbuilt_command(app, "studio", kStudio);
#endif

#if SANDPAPER_WITH_LSP
  auto* lsp = app.add_subcommand("lsp", "serve the Language Server Protocol on stdin/stdout for editors (docs/EDITORS.md)");
  add_common(lsp, o, false);
#else
  add_unbuilt_command(app, "lsp", kLsp);
#endif
  auto* diagnostics = app.add_subcommand("diagnostics", "list every diagnostic code with its severity and meaning");
  bool diagnostics_markdown = false;
  diagnostics->add_flag("--markdown", diagnostics_markdown, "print the markdown table schema/LANGUAGE.md holds");
  diagnostics->add_flag("--json", o.json, "print JSON");

  CalibrateOptions calibrate_opts;
  add_calibrate_command(app, calibrate_opts);
#if SANDPAPER_WITH_EXPERIMENTS
  ExperimentOptions experiment_opts;
  add_experiment_command(app, experiment_opts);
#else
  add_unbuilt_command(app, "experiment", kExperiments);
#endif

  // CLI11's own exit codes (106 for a missing subcommand, ...) are not ours: any usage error is 2,
  // --help and --version are 0.
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  auto needs_input = [&](CLI::App* sub) {
    if (o.file.empty() == o.expression.empty()) {
      std::cerr << "sandpaper " << sub->get_name() << ": give a material file or -e '<expression>' (one of the two)\n";
      return false;
    }
    return true;
  };
  try {
    if (compile->parsed()) {
      const bool batch = compile_inputs.size() > 1 || (compile_inputs.size() == 1 && std::filesystem::is_directory(compile_inputs[0]));
      if (batch) {
        if (!o.expression.empty()) {
          std::cerr << "sandpaper compile: give files and folders, or -e '<expression>', not both\n";
          return kExitUsage;
        }
        return cmd_compile_batch(o, compile_inputs, output);
      }
      if (compile_inputs.size() == 1) o.file = compile_inputs[0];
      if (!needs_input(compile)) return kExitUsage;
      if (!dump_stage.empty()) {
        if (is_gltf_input(o) || is_workspace_input(o) || !output.empty()) {
          std::cerr << "sandpaper compile --dump: dumps one material (.hmat or -e) to stdout; without -o\n";
          return kExitUsage;
        }
        return cmd_dump(o, dump_stage);
      }
      if (is_scene_input(o)) {
#if SANDPAPER_WITH_SHAPES
        return cmd_scene_compile(o, output);
#else
        say_unbuilt("sandpaper compile " + o.file, kShapes);
        return kExitUsage;
#endif
      }
      if (is_gltf_input(o)) {
#if SANDPAPER_WITH_GLTF
        return cmd_compile_gltf(o, output);
#else
        say_unbuilt("sandpaper compile " + o.file, kGltf);
        return kExitUsage;
#endif
      }
      return is_workspace_input(o) ? cmd_workspace_compile(o, output, false) : cmd_compile(o, output, false);
    }
    if (explain->parsed()) {
      if (!needs_input(explain)) return kExitUsage;
      if (is_scene_input(o)) {
#if SANDPAPER_WITH_SHAPES
        return cmd_scene_explain(o);
#else
        say_unbuilt("sandpaper explain " + o.file, kShapes);
        return kExitUsage;
#endif
      }
      if (is_gltf_input(o)) {
#if SANDPAPER_WITH_GLTF
        return cmd_explain_gltf(o);
#else
        say_unbuilt("sandpaper explain " + o.file, kGltf);
        return kExitUsage;
#endif
      }
      return is_workspace_input(o) ? cmd_workspace_compile(o, "", true) : cmd_compile(o, "", true);
    }
    if (run->parsed()) {
      if (!needs_input(run)) return kExitUsage;
      if (is_scene_input(o)) {
#if SANDPAPER_WITH_SHAPES
        return cmd_scene_run(o, play_request);
#else
        say_unbuilt("sandpaper run " + o.file, kShapes);
        return kExitUsage;
#endif
      }
      if (is_workspace_input(o)) {
        if (run->count("--hand-model") || run->count("--replay")) {
          std::cerr << "sandpaper run: --hand-model and --replay play single materials; workspaces use the scripted hand\n";
          return kExitUsage;
        }
        play_request.json = o.json;
        WorkspaceRunOptions ro = workspace_options_of(play_request, *run, crossfade_ms);
        ro.live = ro.live || isatty(STDERR_FILENO);
        return cmd_workspace_run(o, ro);
      }
      // A compiled program needs no compiler: the runtime-only player plays it in a process that
      // never maps the compiler's libraries (docs/performance.md, "A player that is only a runtime").
      if (!watch && o.expression.empty() && argc > 1 && std::string_view(argv[1]) == "run" &&
          (sandpaper::schema::looks_like_patch_file(o.file) || sandpaper::schema::looks_like_workspace_program_file(o.file)
#if SANDPAPER_WITH_SHAPES
           || sandpaper::shapes::looks_like_scene_program_file(o.file)
#endif
               ))
        exec_player(argc, argv);
      if (watch && !run->count("--duration")) play_request.duration_s = 0;
      play_request.live = play_request.live || isatty(STDERR_FILENO);
      o.device_given = run->count("--device") > 0;
      return cmd_run(o, play_request, watch);
    }
    if (shuffle->parsed()) return cmd_movie_shuffle(shuffle_opts, o.json);
    if (show->parsed()) return cmd_movie_show(show_file, o.json);
    if (inspect->parsed()) return cmd_inspect(patch_file, o.json, tables);
#if SANDPAPER_WITH_CURATION
    if (library_catalog->parsed()) return cmd_library_catalog(o);
    if (library->parsed()) {
      if (const int rc = cmd_library_sub(o, library_opts); rc >= 0) return rc;
      return cmd_library(o);
    }
#endif
    if (array->parsed()) return cmd_array(ao);
#if SANDPAPER_WITH_CURATION
    if (preview->parsed()) {
      if (!needs_input(preview)) return kExitUsage;
      return cmd_preview(o, preview_dir, preview_side);
    }
#endif
#if SANDPAPER_WITH_GLTF
    if (export_cmd->parsed()) {
      if (!needs_input(export_cmd)) return kExitUsage;
      return cmd_export(o, export_format, export_output);
    }
#endif
#if SANDPAPER_WITH_STUDIO
    if (studio->parsed()) {
      studio_opts.listen_given = studio->count("--listen") > 0;
      return cmd_studio(o, studio_opts);
    }
#endif
#if SANDPAPER_WITH_SHAPES
    if (probe->parsed()) {
      if (!needs_input(probe)) return kExitUsage;
      return cmd_probe(o, probe_opts);
    }
#endif
    if (devices->parsed()) return udev_rules ? cmd_devices_udev_rules(o) : cmd_devices(o);
#if SANDPAPER_WITH_LSP
    if (lsp->parsed()) return cmd_lsp(o);
#endif
    if (diagnostics->parsed()) return cmd_diagnostics(diagnostics_markdown, o.json);
    if (const int rc = cmd_calibrate(calibrate_opts); rc >= 0) return rc;
#if SANDPAPER_WITH_EXPERIMENTS
    if (const int rc = cmd_experiment(experiment_opts); rc >= 0) return rc;
#endif
    if (const int rc = run_unbuilt_command(app); rc >= 0) return rc;
  } catch (const sandpaper::schema::PatchFormatError& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const sandpaper::schema::InputFileError& e) {
    std::cerr << "sandpaper: error: cannot read " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    // The readers' limits (docs/RELIABILITY.md) are meant to stop this first; if memory still runs
    // out, the input asked for it, so it is the input's fault, said plainly.
    std::cerr << "sandpaper: error: out of memory: the input needs more memory than this machine has "
                 "(docs/RELIABILITY.md lists the limits on inputs)\n";
    return kExitBadInput;
  } catch (const sandpaper::calibration::CalibrationError& e) {
    std::cerr << "sandpaper: calibration error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::invalid_argument& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const std::logic_error& e) {
    std::cerr << "sandpaper: internal error (a bug in Sandpaper, please report it): " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "sandpaper: error: " << e.what() << "\n";
    return kExitUsage;
  }
  return kExitUsage;
}
