// The Python module `sandpaper` (pybind11): compile materials by name or text, read what the compiler
// decided (explain) and the lateral force field as numpy arrays, and play them on the simulated
// joystick with the servo thread running while Python does other things. docs/PYTHON.md.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/data_dirs.hpp"
#include "sandpaper/compiler/explain_json.hpp"
#include "sandpaper/compiler/recovered_height_field.hpp"
#include "sandpaper/experiment/observer.hpp"
#include "sandpaper/runtime/devices/builtin_devices.hpp"
#include "sandpaper/runtime/devices/open_device.hpp"
#include "sandpaper/runtime/patch_evaluator.hpp"
#include "sandpaper/runtime/recording_device.hpp"
#include "sandpaper/sandpaper.h"
#include "sandpaper/sandpaper.hpp"

namespace py = pybind11;
namespace sp = sandpaper;

namespace {

// JSON from the compiler, as Python dicts and lists (the same keys and units as the CLI's --json).
py::object to_python(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

// A failed compile, carried to Python with its diagnostics as data.
struct CompileFailure {
  std::string message;
  nlohmann::json diagnostics;
};

// The compiler with its data, shared by the materials it compiled (explain needs it).
struct PyLibrary {
  std::shared_ptr<const sp::compiler::Compiler> compiler;
  std::filesystem::path library_dir, calibration_dir;
};

// A compiled material: the compile (resolved layers, diagnostics) and the playable program.
struct PyMaterial {
  std::shared_ptr<const sp::compiler::Compiler> compiler;
  std::shared_ptr<const sp::compiler::CompileResult> result;
  sp::Material material;
};

PyLibrary open_library(std::optional<std::filesystem::path> library_dir, std::optional<std::filesystem::path> calibration_dir,
                       const std::string& device) {
  // The same choice and the same message for missing folders as sandpaper::Library.
  auto library = library_dir ? sp::compiler::DataDirChoice{*library_dir, "library_dir="} : sp::compiler::find_library_dir();
  auto calibration =
      calibration_dir ? sp::compiler::DataDirChoice{*calibration_dir, "calibration_dir="} : sp::compiler::find_calibration_dir();
  if (auto missing = sp::compiler::missing_data_dirs_message({{"library", library}, {"calibration", calibration}});
      !missing.empty())
    throw sp::Error(missing);
  try {
    auto c = std::make_shared<const sp::compiler::Compiler>(
        sp::compiler::CompileOptions{device, library.dir, calibration.dir, {}});
    return PyLibrary{std::move(c), library.dir, calibration.dir};
  } catch (const std::exception& e) {  // malformed calibration, unknown device (the message lists the known ones)
    throw sp::Error(e.what());
  }
}

PyMaterial compile(const PyLibrary& lib, const std::string& text) {
  auto result = std::make_shared<sp::compiler::CompileResult>(lib.compiler->compile_text(text, "<compile>"));
  if (!result->ok())
    throw CompileFailure{sp::compiler::format_diagnostics(result->diagnostics),
                         sp::compiler::diagnostics_json(result->diagnostics)};
  sp::Material material(*result->program);
  return PyMaterial{lib.compiler, std::move(result), std::move(material)};
}

std::vector<std::string> roughness_levels(const PyLibrary& lib) {
  std::vector<std::string> out;
  for (const auto& l : lib.compiler->calibration().roughness_levels()) out.push_back(l.name);
  return out;
}

constexpr int kMaxFieldPoints = 4096;
// A grid point lands within this fraction of each ridge's peak force, wherever the grid falls.
constexpr double kPeakLevel = 0.95;

// The width (m) of the narrowest ridge of a grating's force table (one period of `period_m`, evenly
// sampled, repeating): the run of samples around each local peak of |F| at or above kPeakLevel of
// it. A grid that fine meets every peak within 5 %; the thesis' smoothing (sigma = 6/256 of the
// period) gives about 1/67 of the period.
double narrowest_ridge_m(const std::vector<float>& force_N, double period_m) {
  const std::size_t n = force_N.size();
  float top = 0;
  for (float f : force_N) top = std::max(top, std::abs(f));
  double width = period_m;
  if (n < 2 || top <= 0) return width;
  auto at = [&](std::size_t i) { return std::abs(force_N[i % n]); };
  for (std::size_t i = 0; i < n; ++i) {
    const float a = at(i);
    if (a < 0.05f * top || a < at(i + n - 1) || a < at(i + 1)) continue;  // not a peak, or a negligible one
    std::size_t left = 0, right = 0;
    while (left + right + 1 < n && at(i + n - left - 1) >= kPeakLevel * a) ++left;
    while (left + right + 1 < n && at(i + right + 1) >= kPeakLevel * a) ++right;
    width = std::min(width, static_cast<double>(left + right + 1) * period_m / static_cast<double>(n));
  }
  return width;
}

// The widest grid spacing (m) that shows `program`'s texture without aliasing its ridges: each
// grating's narrowest ridge, each height field's sample spacing; infinity when no term has one.
double finest_spacing_m(const sp::schema::PatchProgram& program) {
  double s = std::numeric_limits<double>::infinity();
  for (const auto& term : program.terms) {
    if (const auto* g = std::get_if<sp::schema::GratingTerm>(&term)) s = std::min(s, narrowest_ridge_m(g->force_N, g->period_m));
    if (const auto* h = std::get_if<sp::schema::HeightFieldTerm>(&term))
      s = std::min({s, h->spacing_m[0], h->spacing_m[1]});
  }
  return s;
}

// The lateral force a still hand feels at each point of an n x n grid over a window centred on the
// patch (the whole patch by default; row 0 at -y): what the height field's gradient and the other
// position-dependent terms give (F = -k grad h, thesis 3.4). n by default: the fewest points that
// resolve the texture (finest_spacing_m). A grid too coarse for the texture would alias its ridges
// and show a weaker field than the hand feels, so it is refused (ValueError naming the n needed).
py::dict lateral_force_field(const PyMaterial& m, std::optional<int> n_given, std::optional<std::vector<double>> window_m) {
  const auto& program = m.material.program();
  double width = program.size_m[0], height = program.size_m[1];
  if (window_m) {
    if (window_m->size() != 2 || !((*window_m)[0] > 0) || !((*window_m)[1] > 0) || !std::isfinite((*window_m)[0]) ||
        !std::isfinite((*window_m)[1]))
      throw py::value_error("window_m takes a width and a height in metres, both > 0");
    width = (*window_m)[0];
    height = (*window_m)[1];
  }
  const double finest = finest_spacing_m(program);
  const double span = std::max(width, height);
  const double needed_exact = std::isfinite(finest) ? std::ceil(span / finest) : 2;
  const int needed = static_cast<int>(std::min<double>(std::max(needed_exact, 2.0), kMaxFieldPoints + 1.0));
  auto too_coarse = [&](int n) {
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "an n = %d grid over %.4g x %.4g mm samples every %.3g mm, coarser than the texture's finest "
                  "scale (%.3g mm: a grating's narrowest ridge at 95 %% of its peak, or a height field's sample spacing), so it would "
                  "alias the ridges and show a weaker field than the hand feels; %s",
                  n, width * 1e3, height * 1e3, span / n * 1e3, finest * 1e3,
                  needed_exact <= kMaxFieldPoints
                      ? ("use n >= " + std::to_string(needed)).c_str()
                      : "no grid of up to 4096 points covers this window: ask for a smaller window_m=(width, height)");
    return py::value_error(buf);
  };
  int n = n_given ? *n_given : needed;
  if (n_given && (n < 2 || n > kMaxFieldPoints)) throw py::value_error("n must be 2 to 4096 points a side");
  if (!n_given && needed_exact > kMaxFieldPoints) throw too_coarse(kMaxFieldPoints);
  if (span / n > finest * (1 + 1e-9)) throw too_coarse(n);
  py::array_t<double> x({n}), y({n}), fx({n, n}), fy({n, n});
  auto xs = x.mutable_unchecked<1>(), ys = y.mutable_unchecked<1>();
  auto fxs = fx.mutable_unchecked<2>(), fys = fy.mutable_unchecked<2>();
  for (int i = 0; i < n; ++i) {
    xs(i) = width * ((i + 0.5) / n - 0.5);
    ys(i) = height * ((i + 0.5) / n - 0.5);
  }
  {
    py::gil_scoped_release release;
    sp::runtime::PatchEvaluator evaluator(program);
    sp::runtime::HandState hand;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        hand.position_m = {xs(c), ys(r)};
        evaluator.reset_rt(hand);  // state (adhesion, masses) at rest under the hand
        const auto f = evaluator.force_rt(hand, 0.0);
        fxs(r, c) = f.x;
        fys(r, c) = f.y;
      }
  }
  py::dict out;
  out["x_m"] = x;
  out["y_m"] = y;
  out["fx_N"] = fx;
  out["fy_N"] = fy;
  return out;
}

// The heights the texture is the gradient of (compiler/recovered_height_field.hpp), as numpy arrays.
py::dict height_field(const PyMaterial& m) {
  std::string why;
  const auto* resolved = m.result->material ? &*m.result->material : nullptr;
  const auto t = sp::compiler::recover_height_field(m.material.program(), resolved, why);
  if (!t) throw sp::Error("no height field for '" + m.material.name() + "': " + why);
  py::array_t<double> x({t->nx}), y({t->ny}), h({t->ny, t->nx});
  auto xs = x.mutable_unchecked<1>(), ys = y.mutable_unchecked<1>();
  auto hs = h.mutable_unchecked<2>();
  for (int i = 0; i < t->nx; ++i) xs(i) = t->origin_m[0] + i * t->spacing_m[0];
  for (int j = 0; j < t->ny; ++j) ys(j) = t->origin_m[1] + j * t->spacing_m[1];
  for (int j = 0; j < t->ny; ++j)
    for (int i = 0; i < t->nx; ++i) hs(j, i) = t->h_m[static_cast<std::size_t>(j) * static_cast<std::size_t>(t->nx) + static_cast<std::size_t>(i)];
  py::dict out;
  out["kind"] = t->kind;
  out["x_m"] = x;
  out["y_m"] = y;
  out["h_m"] = h;
  out["k_N"] = t->k_N;
  out["nominal"] = t->nominal;
  out["repeat"] = t->repeat;
  if (t->kind == "grating") {
    out["period_m"] = t->period_m;
    out["orientation_rad"] = t->orientation_rad;
  }
  return out;
}

// The experiments' simulated observer (experiments, docs/EXPERIMENTS.md), for sessions run
// from Python: the same answers `sandpaper experiment run --observer simulated:...` gives.
struct PyObserver {
  std::unique_ptr<sp::experiment::Observer> observer;
  int trials = 0;
};

py::dict report_dict(const sp::runtime::ServoReport& r) {
  py::dict d;
  d["ticks"] = r.ticks;
  d["rate_hz"] = r.rate_hz;
  d["felt_max_lateral_force_N"] = r.felt_max_lateral_force_N;
  d["stop_cause"] = sp::runtime::stop_cause_name(r.stop_cause);
  d["period_p50_us"] = r.period_p50_us;
  d["period_p99_us"] = r.period_p99_us;
  d["jitter_us"] = r.jitter_us;
  d["overruns"] = r.overruns;
  d["clamped_ticks"] = r.clamped_ticks;
  d["realtime_scheduling"] = r.realtime_scheduling;
  return d;
}

// A player and whether its device records ticks (Player.simulated(record_ticks=...)).
struct PyPlayer {
  sp::Player player;
  sp::runtime::RecordingDevice* recorder = nullptr;
  // The library Player.load("name") compiles through: the default folders, for the player's device.
  std::optional<PyLibrary> library;
};

sp::runtime::HandScript hand_script(const std::string& path, double speed_m_s, double amplitude_m) {
  sp::runtime::HandScript s;
  if (path == "scan") s.path = sp::runtime::HandPath::Scan;
  else if (path == "circle") s.path = sp::runtime::HandPath::Circle;
  else throw py::value_error("hand must be \"scan\" or \"circle\", not \"" + path + "\"");
  if (!(speed_m_s > 0) || !(amplitude_m > 0)) throw py::value_error("speed_m_s and amplitude_m must be positive");
  s.speed_m_s = speed_m_s;
  s.amplitude_m = amplitude_m;
  return s;
}

#ifdef SANDPAPER_MODULE_DIR_TO_DATA
// The installed module: the data of the install it belongs to, from where this shared object lies
// (<prefix>/lib/python3.X/dist-packages/ -> <prefix>/share/sandpaper), wherever the prefix was moved.
void register_installed_data_dir() {
  Dl_info info{};
  if (!dladdr(reinterpret_cast<void*>(&register_installed_data_dir), &info) || !info.dli_fname) return;
  static const std::string module_file = std::filesystem::absolute(info.dli_fname).string();
  sp::compiler::set_package_data_dir_nonrt(module_file.c_str(), SANDPAPER_MODULE_DIR_TO_DATA);
}
#endif

}  // namespace

PYBIND11_MODULE(sandpaper, m) {
#ifdef SANDPAPER_MODULE_DIR_TO_DATA
  register_installed_data_dir();
#endif
  m.doc() = "Sandpaper: compile haptic materials by name or description and play them (docs/PYTHON.md)";
  m.attr("__version__") = sp_version();

  static py::exception<sp::Error> error(m, "Error");
  static py::exception<sp::UnknownLevel> unknown_level(m, "UnknownLevel", error.ptr());
  static py::exception<sp::DeviceError> device_error(m, "DeviceError", error.ptr());
  static py::exception<CompileFailure> compile_error(m, "CompileError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const CompileFailure& e) {
      // An instance with the diagnostics as data: [{code, severity, location, line, column, message, suggestion}].
      py::object instance = py::handle(compile_error.ptr())(e.message);
      instance.attr("diagnostics") = to_python(e.diagnostics);
      PyErr_SetObject(compile_error.ptr(), instance.ptr());
    } catch (const sp::UnknownLevel& e) {
      py::object instance = py::handle(unknown_level.ptr())(e.what());
      instance.attr("known") = e.known();
      PyErr_SetObject(unknown_level.ptr(), instance.ptr());
    } catch (const sp::DeviceError& e) {
      device_error(e.what());
    } catch (const sp::Error& e) {
      error(e.what());
    }
  });

  py::class_<PyMaterial>(m, "Material", "A compiled material: a patch program ready to play (SI units).")
      .def_property_readonly("name", [](const PyMaterial& x) { return x.material.name(); })
      .def_property_readonly("compiled_max_lateral_force_N", [](const PyMaterial& x) { return x.material.compiled_max_lateral_force_N(); },
                             "the texture's maximum lateral force as compiled for the device, N")
      .def_property_readonly("compiled_roughness", [](const PyMaterial& x) { return x.material.compiled_roughness(); },
                             "ratio-scale roughness the roughness map predicts (Minsky 1995, Fig. 19)")
      .def_property_readonly("size_m", [](const PyMaterial& x) {
        return std::vector<double>{x.material.program().size_m[0], x.material.program().size_m[1]};
      }, "patch width and height, m")
      .def_property_readonly("warnings", [](const PyMaterial& x) { return x.material.warnings(); })
      .def("explain", [](const PyMaterial& x, std::optional<double> design_speed_m_s) {
        if (design_speed_m_s && !(std::isfinite(*design_speed_m_s) && *design_speed_m_s > 0))
          throw py::value_error("design_speed_m_s must be a finite hand speed above 0 m/s (None: no design speed), not " +
                                std::string(py::str(py::float_(*design_speed_m_s))));
        auto j = sp::compiler::compile_json(*x.result, std::nullopt);
        j.erase("output");
        j.update(sp::compiler::explain_json(*x.result->material, *x.result->program, *x.compiler, design_speed_m_s.value_or(0.0)));
        return to_python(j);
      }, py::arg("design_speed_m_s") = py::none(),
         "what the compiler decided, as `sandpaper explain --json` prints it: a dict. design_speed_m_s: the hand "
         "speed the material is designed for, m/s, finite and above 0 (else ValueError), or None")
      .def("height_field", &height_field,
           "the heights the texture is the gradient of (F = -k_N grad h): {kind, x_m, y_m, h_m (ny, nx), k_N, nominal, "
           "repeat[, period_m, orientation_rad]}; a grating is one period along its force direction (ny = 1); "
           "nominal: no depth was stated, so the heights are scaled to a steepest slope of 1. Raises Error for a "
           "material with no grating or height map")
      .def("lateral_force_field", &lateral_force_field, py::arg("n") = py::none(), py::arg("window_m") = py::none(),
           "the lateral force a still hand feels on an n x n grid over the patch, or over a window (width, height "
           "in m) centred on it: {x_m, y_m, fx_N, fy_N} as numpy arrays. n defaults to the fewest points that "
           "resolve the texture (every grating ridge met within 5 % of its peak, one point per height-field sample); a "
           "coarser n raises ValueError")
      .def("__repr__", [](const PyMaterial& x) {
        return "<sandpaper.Material " + x.material.name() + ": " + std::to_string(x.material.compiled_max_lateral_force_N()) + " N>";
      });

  py::class_<PyLibrary>(m, "Library", "The world haptics library with its calibration, compiling for one device.")
      .def(py::init(&open_library), py::arg("library_dir") = py::none(), py::arg("calibration_dir") = py::none(),
           py::arg("device") = "sim")
      .def("compile", &compile, py::arg("text"), py::call_guard<py::gil_scoped_release>(),
           "a library name (\"corduroy\") or material statements; raises CompileError")
      .def("roughness_level", [](const PyLibrary& lib, const std::string& level) {
        if (!lib.compiler->calibration().find_level(level)) throw sp::UnknownLevel(level, roughness_levels(lib));
        py::gil_scoped_release release;
        return compile(lib, "roughness " + level);
      }, py::arg("level"), "a named roughness level (\"coarse\") on the reference texture; raises UnknownLevel")
      .def("roughness_levels", &roughness_levels, "roughness level names, weakest first")
      .def("level", [](const PyLibrary& lib, const std::string& percept, const std::string& level) {
        bool known = false;
        std::vector<std::string> names;
        for (const auto* l : lib.compiler->calibration().levels(percept)) {
          names.push_back(l->name);
          known |= l->name == level;
        }
        if (!known) throw sp::UnknownLevel(level, names, percept, sp::percepts_with_levels(lib.compiler->calibration()));
        py::gil_scoped_release release;
        return compile(lib, percept + " " + level);
      }, py::arg("percept"), py::arg("level"),
         "a named level of any percept with levels (\"softness\", \"soft\"), alone, as `softness soft`; raises UnknownLevel")
      .def("levels", [](const PyLibrary& lib, const std::string& percept) {
        std::vector<std::string> out;
        for (const auto* l : lib.compiler->calibration().levels(percept)) out.push_back(l->name);
        return out;
      }, py::arg("percept"), "a percept's level names, weakest first (empty: none)")
      .def("names", [](const PyLibrary& lib) { return lib.compiler->library().names(); }, "entry names, sorted")
      .def_readonly("library_dir", &PyLibrary::library_dir)
      .def_readonly("calibration_dir", &PyLibrary::calibration_dir);

  py::class_<PyObserver>(m, "SimulatedObserver",
                         "The experiments' simulated observer (docs/EXPERIMENTS.md): magnitude estimates "
                         "modulus * F^exponent with log-normal noise, two-interval choices at a Weber fraction.")
      .def(py::init([](const std::string& spec, const std::string& subject) {
             try {
               auto parsed = sp::experiment::parse_simulated_observer("simulated:" + spec);
               // The CLI takes a missing exponent from the percept's compile map; here there is none.
               if (!parsed.exponent && !parsed.dimension.empty() && parsed.dimension != "roughness")
                 throw std::invalid_argument("give exponent= for dimension " + parsed.dimension +
                                             " (e.g. the slope of its compile map in calibration/maps/)");
               return PyObserver{sp::experiment::make_simulated_observer(parsed, subject), 0};
             } catch (const std::invalid_argument& e) {
               throw py::value_error(e.what());
             }
           }),
           py::arg("spec") = "", py::arg("subject") = "S01",
           "spec as after `--observer simulated:`, e.g. \"exponent=0.76,noise=0.15,seed=3\"; each subject "
           "draws its own modulus")
      .def("estimate", [](PyObserver& o, double felt_force_N, double period_m, bool confidence) {
        if (!(felt_force_N >= 0)) throw py::value_error("felt_force_N must be a force in newtons, >= 0");
        sp::experiment::Trial t;
        t.index = o.trials++;
        t.stimuli = {0};
        sp::experiment::Presented p{{"stimulus"}, {felt_force_N}, {felt_force_N}, {period_m}};
        return *o.observer->estimate(t, p, confidence);
      }, py::arg("felt_force_N"), py::arg("period_m") = 0.0, py::arg("confidence") = false,
         "a magnitude estimate (> 0) of a stimulus felt at this peak lateral force (N), or with "
         "confidence=True a confidence 0-100 % that it was a texture")
      .def("choose_interval", [](PyObserver& o, double first_N, double second_N) {
        sp::experiment::Trial t;
        t.index = o.trials++;
        t.stimuli = {0, 1};
        sp::experiment::Presented p{{"first", "second"}, {first_N, second_N}, {first_N, second_N}, {0.0, 0.0}};
        return *o.observer->choose_interval(t, p);
      }, py::arg("first_N"), py::arg("second_N"), "two-interval: 1 or 2, the interval that felt stronger");

  py::class_<PyPlayer>(m, "Player", "Plays materials on a device on a servo thread of its own.")
      .def_static("simulated", [](std::size_t record_ticks, const std::string& hand, double speed_m_s, double amplitude_m) {
        // Through the device factory, as every caller: the simulated joystick of sim.toml.
        sp::runtime::DeviceSpec spec;
        spec.script = hand_script(hand, speed_m_s, amplitude_m);
        spec.record_ticks = record_ticks;
        auto opened = sp::runtime::open_device(sp::runtime::builtin_devices(), std::move(spec));
        auto* recorder = opened.recording;
        return std::make_unique<PyPlayer>(PyPlayer{sp::Player(std::move(opened.device)), recorder, std::nullopt});
      }, py::arg("record_ticks") = 0, py::arg("hand") = "scan", py::arg("speed_m_s") = 0.05, py::arg("amplitude_m") = 0.03,
         "the simulated joystick (10 N, calibration/devices/sim.toml) with a scripted hand; keeps the first "
         "record_ticks ticks for trace()")
      .def_static("usb", [](const PyLibrary& lib) {
        return std::make_unique<PyPlayer>(PyPlayer{sp::Player::usb(lib.compiler->calibration()), nullptr, std::nullopt});
      }, py::arg("library"),
         "the first USB HID PID force-feedback joystick plugged in that the library's calibration knows "
         "(docs/USB_PID.md); compile its materials with Library(device=player.device_calibration). "
         "Raises DeviceError when there is none or it cannot be opened")
      .def_static("open", [](const PyLibrary& lib, const std::string& device, bool uncalibrated) {
        auto p = std::make_unique<PyPlayer>(PyPlayer{
            sp::Player::open(lib.compiler->calibration(), device, {.uncalibrated = uncalibrated}), nullptr, std::nullopt});
        // A warnings filter set to "error" raises it, as Python's own warnings do.
        if (!p->player.warning().empty() && PyErr_WarnEx(PyExc_RuntimeWarning, p->player.warning().c_str(), 1) < 0)
          throw py::error_already_set();
        return p;
      }, py::arg("library"), py::arg("device"), py::kw_only(), py::arg("uncalibrated") = false,
         "a calibrated joystick found along the path `device` names (docs/DEVICES.md): 'usb' (as usb()), "
         "'hidraw' (its hidraw node, the kernel's driver left bound, no root), 'hidraw:/dev/hidrawN', "
         "'evdev' or 'evdev:/dev/input/eventN' (the kernel's own force feedback, no root). "
         "uncalibrated=True: an evdev device no calibration file names, with the uncalibrated-evdev profile "
         "(a RuntimeWarning and Player.warning say so). "
         "Raises DeviceError when there is none, it cannot be opened, or the device is not on the bus")
      .def_property_readonly("warning", [](const PyPlayer& p) { return p.player.warning(); },
         "what to tell a person before playing (a profile's assumed scale), or ''")
      .def_property_readonly("device_calibration", [](const PyPlayer& p) { return p.player.device_calibration(); },
         "the device calibration materials must be compiled for (usb); empty for the simulated joystick")
      .def("load", [](PyPlayer& p, const PyMaterial& x) { p.player.load(x.material); }, py::arg("material"),
           "plays a compiled Material (crossfading from what plays now)")
      .def("load", [](PyPlayer& p, const std::string& text) {
        if (!p.library) {
          const std::string device = p.player.device_calibration();
          p.library = open_library(std::nullopt, std::nullopt, device.empty() ? "sim" : device);
        }
        PyMaterial material = [&] {
          py::gil_scoped_release release;
          return compile(*p.library, text);
        }();
        p.player.load(material.material);
        return material;
      }, py::arg("material"),
         "compiles a library name (\"corduroy\") or material statements through the default library for the "
         "player's device, plays it, and returns the Material; raises CompileError")
      .def("start", [](PyPlayer& p, double rate_hz, double duration_s) {
        try {
          p.player.start({.rate_hz = rate_hz, .duration_s = duration_s});
        } catch (const std::invalid_argument& e) {
          throw py::value_error(e.what());
        }
      }, py::arg("rate_hz") = 1000.0, py::arg("duration_s") = 0.0,
         "starts the servo thread (rate 900 - 10000 Hz; duration 0: until stop()) and returns at once")
      .def("stop", [](PyPlayer& p) {
        sp::runtime::ServoReport r;
        {
          py::gil_scoped_release release;
          r = p.player.stop();
        }
        return report_dict(r);
      }, "stops at the next tick, waits, and returns the run's report (a dict)")
      .def("wait", [](PyPlayer& p) {
        sp::runtime::ServoReport r;
        {
          py::gil_scoped_release release;
          r = p.player.wait();
        }
        return report_dict(r);
      }, "waits for the run to end (its duration, or a fault) and returns its report (a dict)")
      .def_property_readonly("playing", [](const PyPlayer& p) { return p.player.playing(); })
      .def("trace", [](const PyPlayer& p) {
        if (p.player.playing()) throw sp::Error("trace() is read after the run: stop() or wait() first");
        const auto& rec = p.recorder->records();
        py::array_t<double> a({static_cast<py::ssize_t>(rec.size()), py::ssize_t{5}});
        auto v = a.mutable_unchecked<2>();
        for (std::size_t i = 0; i < rec.size(); ++i) {
          const auto k = static_cast<py::ssize_t>(i);
          v(k, 0) = rec[i].t_s;
          v(k, 1) = rec[i].position_m.x;
          v(k, 2) = rec[i].position_m.y;
          v(k, 3) = rec[i].force_N.x;
          v(k, 4) = rec[i].force_N.y;
        }
        return a;
      }, "the recorded ticks as an (n, 5) array: t_s, x_m, y_m, fx_N, fy_N");
}
