// The C API (sandpaper/sandpaper.h) over the C++ one: handles own C++ objects, every entry point
// catches everything, and the message of what failed waits in a thread-local string.
#include "sandpaper/sandpaper.h"

#include <exception>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "sandpaper/compiler/data_dirs.hpp"
#include "sandpaper/sandpaper.hpp"

#ifndef SANDPAPER_VERSION
#error "c_api.cpp is built by api/CMakeLists.txt with SANDPAPER_VERSION"
#endif

struct sp_library {
  sandpaper::Library library;
};
struct sp_material {
  sandpaper::Material material;
  std::string warnings;  // kept for sp_material_warnings' pointer
};
struct sp_player {
  sandpaper::Player player;
  bool loaded = false;
  bool started = false;  // from start until stop or wait
};

namespace {

thread_local std::string last_error;

sp_status fail(sp_status status, std::string message) {
  last_error = std::move(message);
  return status;
}

// Every entry point's body runs in here: the C++ API's exceptions become status codes.
template <class F>
sp_status guarded(F&& body) noexcept {
  try {
    return body();
  } catch (const sandpaper::CompileError& e) {
    return fail(SP_ERROR_COMPILE, e.what());
  } catch (const sandpaper::DeviceError& e) {
    return fail(SP_ERROR_DEVICE, e.what());
  } catch (const sandpaper::UnknownLevel& e) {
    return fail(SP_ERROR_UNKNOWN_LEVEL, e.what());
  } catch (const sandpaper::Error& e) {
    return fail(SP_ERROR_DATA, e.what());
  } catch (const std::invalid_argument& e) {  // rates, durations: the runtime's checks
    return fail(SP_ERROR_ARGUMENT, e.what());
  } catch (const std::bad_alloc&) {
    return fail(SP_ERROR_INTERNAL, "out of memory");
  } catch (const std::exception& e) {
    return fail(SP_ERROR_INTERNAL, std::string("internal error (please report it): ") + e.what());
  } catch (...) {
    return fail(SP_ERROR_INTERNAL, "internal error (please report it): unknown exception");
  }
}

sp_status null_argument(const char* function, const char* argument) {
  return fail(SP_ERROR_ARGUMENT, std::string(function) + ": `" + argument + "` is NULL");
}

void fill(sp_report* out, const sandpaper::runtime::ServoReport& r) {
  if (!out) return;
  out->ticks = r.ticks;
  out->rate_hz = r.rate_hz;
  out->felt_max_lateral_force_N = r.felt_max_lateral_force_N;
  out->clamped_ticks = r.clamped_ticks;
  out->overruns = r.overruns;
  out->stop_cause = static_cast<int>(r.stop_cause);
  out->stop_cause_name = sandpaper::runtime::stop_cause_name(r.stop_cause);
}

sp_status new_material(sandpaper::Material m, sp_material** out) {
  std::string warnings;
  for (const auto& w : m.warnings()) warnings += w + "\n";
  *out = new sp_material{std::move(m), std::move(warnings)};
  return SP_OK;
}

}  // namespace

extern "C" {

const char* sp_version(void) { return SANDPAPER_VERSION; }

const char* sp_last_error(void) { return last_error.c_str(); }

void sp_register_package_data_dir(const char* header_file, const char* header_dir_to_data) {
  sandpaper::compiler::set_package_data_dir_nonrt(header_file, header_dir_to_data);
}

sp_status sp_library_open(const char* library_dir, const char* calibration_dir, const char* device, sp_library** out) {
  if (!out) return null_argument("sp_library_open", "out");
  return guarded([&] {
    sandpaper::LibraryOptions options;
    if (library_dir) options.library_dir = library_dir;
    if (calibration_dir) options.calibration_dir = calibration_dir;
    if (device) options.device = device;
    *out = new sp_library{sandpaper::Library(std::move(options))};
    return SP_OK;
  });
}

void sp_library_close(sp_library* library) { delete library; }

sp_status sp_library_compile(const sp_library* library, const char* name_or_statements, sp_material** out) {
  if (!library) return null_argument("sp_library_compile", "library");
  if (!name_or_statements) return null_argument("sp_library_compile", "name_or_statements");
  if (!out) return null_argument("sp_library_compile", "out");
  return guarded([&] { return new_material(library->library.compile(name_or_statements), out); });
}

sp_status sp_library_roughness_level(const sp_library* library, const char* level, sp_material** out) {
  if (!library) return null_argument("sp_library_roughness_level", "library");
  if (!level) return null_argument("sp_library_roughness_level", "level");
  if (!out) return null_argument("sp_library_roughness_level", "out");
  return guarded([&] { return new_material(library->library.roughness_level(level), out); });
}

sp_status sp_library_level(const sp_library* library, const char* percept, const char* level, sp_material** out) {
  if (!library) return null_argument("sp_library_level", "library");
  if (!percept) return null_argument("sp_library_level", "percept");
  if (!level) return null_argument("sp_library_level", "level");
  if (!out) return null_argument("sp_library_level", "out");
  return guarded([&] { return new_material(library->library.level(percept, level), out); });
}

void sp_material_free(sp_material* material) { delete material; }

const char* sp_material_name(const sp_material* material) {
  return material ? material->material.name().c_str() : "";
}
double sp_material_compiled_max_lateral_force_N(const sp_material* material) {
  return material ? material->material.compiled_max_lateral_force_N() : 0.0;
}
double sp_material_compiled_roughness(const sp_material* material) { return material ? material->material.compiled_roughness() : 0.0; }
const char* sp_material_warnings(const sp_material* material) { return material ? material->warnings.c_str() : ""; }

sp_status sp_player_open_simulated(sp_player** out) {
  if (!out) return null_argument("sp_player_open_simulated", "out");
  return guarded([&] {
    *out = new sp_player{sandpaper::Player::simulated()};
    return SP_OK;
  });
}

sp_status sp_player_open_usb(const sp_library* library, sp_player** out) {
  if (!library) return null_argument("sp_player_open_usb", "library");
  if (!out) return null_argument("sp_player_open_usb", "out");
  return guarded([&] {
    *out = new sp_player{sandpaper::Player::usb(library->library)};
    return SP_OK;
  });
}

sp_status sp_player_open_device(const sp_library* library, const char* device, sp_player** out) {
  if (!library) return null_argument("sp_player_open_device", "library");
  if (!device) return null_argument("sp_player_open_device", "device");
  if (!out) return null_argument("sp_player_open_device", "out");
  return guarded([&] {
    *out = new sp_player{sandpaper::Player::open(library->library, device)};
    return SP_OK;
  });
}

sp_status sp_player_open_device_uncalibrated(const sp_library* library, const char* device, sp_player** out) {
  if (!library) return null_argument("sp_player_open_device_uncalibrated", "library");
  if (!device) return null_argument("sp_player_open_device_uncalibrated", "device");
  if (!out) return null_argument("sp_player_open_device_uncalibrated", "out");
  return guarded([&] {
    *out = new sp_player{sandpaper::Player::open(library->library, device, {.uncalibrated = true})};
    return SP_OK;
  });
}

const char* sp_player_warning(const sp_player* player) { return player ? player->player.warning().c_str() : ""; }

const char* sp_player_device_calibration(const sp_player* player) {
  return player ? player->player.device_calibration().c_str() : "";
}

void sp_player_close(sp_player* player) { delete player; }  // ~Player stops and joins

sp_status sp_player_load(sp_player* player, const sp_material* material) {
  if (!player) return null_argument("sp_player_load", "player");
  if (!material) return null_argument("sp_player_load", "material");
  return guarded([&] {
    player->player.load(material->material);
    player->loaded = true;
    return SP_OK;
  });
}

sp_status sp_player_start(sp_player* player, double rate_hz, double duration_s) {
  if (!player) return null_argument("sp_player_start", "player");
  if (!player->loaded) return fail(SP_ERROR_STATE, "sp_player_start: nothing to play; sp_player_load a material first");
  if (player->player.playing())
    return fail(SP_ERROR_STATE, "sp_player_start: already playing; sp_player_stop or sp_player_wait first");
  return guarded([&] {
    player->player.start({.rate_hz = rate_hz, .duration_s = duration_s});
    player->started = true;
    return SP_OK;
  });
}

sp_status sp_player_stop(sp_player* player, sp_report* report) {
  if (!player) return null_argument("sp_player_stop", "player");
  if (!player->started) return fail(SP_ERROR_STATE, "sp_player_stop: not playing; sp_player_start first");
  return guarded([&] {
    player->started = false;
    fill(report, player->player.stop());
    return SP_OK;
  });
}

sp_status sp_player_wait(sp_player* player, sp_report* report) {
  if (!player) return null_argument("sp_player_wait", "player");
  if (!player->started) return fail(SP_ERROR_STATE, "sp_player_wait: not playing; sp_player_start first");
  return guarded([&] {
    player->started = false;
    fill(report, player->player.wait());
    return SP_OK;
  });
}

int sp_player_playing(const sp_player* player) { return player && player->player.playing() ? 1 : 0; }

}  // extern "C"
