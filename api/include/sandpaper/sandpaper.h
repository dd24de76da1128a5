#ifndef SANDPAPER_SANDPAPER_H
#define SANDPAPER_SANDPAPER_H
/* Sandpaper from C (and from anything that calls C: C# P/Invoke for Unity, Unreal, Python ctypes):
 * compile a material by name or text, and play it on a device. A thin layer over the C++ API
 * (sandpaper/sandpaper.hpp); docs/API.md, "From C", has the whole story.
 *
 *   sp_library* lib;  sp_material* m;  sp_player* p;  sp_report r;
 *   if (sp_library_open(NULL, NULL, NULL, &lib) != SP_OK) { puts(sp_last_error()); return 1; }
 *   sp_library_compile(lib, "corduroy", &m);
 *   sp_player_open_simulated(&p);
 *   sp_player_load(p, m);
 *   sp_player_start(p, 1000.0, 0.5);
 *   sp_player_wait(p, &r);
 *   sp_player_close(p);  sp_material_free(m);  sp_library_close(lib);
 *
 * Rules for every function:
 * - Returns an sp_status. On anything but SP_OK, sp_last_error() says what went wrong and how to fix
 *   it (for SP_ERROR_COMPILE: the diagnostics as `sandpaper compile` prints them, file:line:col with
 *   a caret), and every out-parameter is left unchanged. No C++ exception ever crosses this boundary.
 * - Handles are opaque. The caller owns what an *_open / *_compile / *_roughness_level call returns
 *   and frees it with the matching *_close / *_free, which take NULL as a no-op. A material may be
 *   freed while a player plays it (the player keeps its own reference).
 * - Strings are UTF-8 and NUL-terminated. Returned strings belong to the library: sp_last_error()'s
 *   until the next call on the same thread, a material's until it is freed.
 * - One handle is used from one thread at a time; different handles may be used from different
 *   threads. sp_last_error() is per thread.
 * - Units are SI: newtons, hertz, seconds.
 */
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum sp_status {
  SP_OK = 0,
  SP_ERROR_ARGUMENT = 1,       /* a NULL handle or out-parameter, a rate or duration out of range */
  SP_ERROR_DATA = 2,           /* library or calibration missing or malformed, unknown device */
  SP_ERROR_COMPILE = 3,        /* the material did not compile: sp_last_error() has the diagnostics */
  SP_ERROR_UNKNOWN_LEVEL = 4,  /* a level name calibration/levels/ does not define for its percept */
  SP_ERROR_STATE = 5,          /* start with nothing loaded or while playing; stop or wait before start */
  SP_ERROR_DEVICE = 6,         /* no joystick plugged in that the calibration knows, it cannot be opened, or a
                                  material compiled for another device */
  SP_ERROR_INTERNAL = 99       /* a defect in Sandpaper (or out of memory): please report it */
} sp_status;

typedef struct sp_library sp_library;
typedef struct sp_material sp_material;
typedef struct sp_player sp_player;

/* A run's summary (runtime::ServoReport). stop_cause_name is stable snake_case, "completed",
 * "stop_requested", "device_unplugged", ... (docs/RUNTIME.md); it is a static string. */
typedef struct sp_report {
  uint64_t ticks;
  double rate_hz;             /* achieved servo rate, Hz */
  double felt_max_lateral_force_N; /* largest |F| written to the device, N */
  uint64_t clamped_ticks;     /* ticks limited to the device's maximum force */
  uint64_t overruns;          /* ticks that started later than half a period after their deadline */
  int stop_cause;             /* runtime::StopCause as an int; 0 = completed */
  const char* stop_cause_name;
} sp_report;

/* The version of the library linked, "0.1.0". */
const char* sp_version(void);

/* The last failed call's message on this thread ("" when none has failed). */
const char* sp_last_error(void);

/* Opens a library and its calibration for a device. NULL for any argument: the default
 * (library and calibration: $SANDPAPER_LIBRARY / $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR, the
 * installed package's; device "sim"). SP_ERROR_DATA names every missing directory at once. */
sp_status sp_library_open(const char* library_dir, const char* calibration_dir, const char* device, sp_library** out);
void sp_library_close(sp_library* library);

/* Compiles a library name ("corduroy") or material statements ("grating period 2.5 mm; depth 0.3 mm"). */
sp_status sp_library_compile(const sp_library* library, const char* name_or_statements, sp_material** out);
/* A named roughness level ("coarse") on the library's reference texture, as `roughness coarse`. */
sp_status sp_library_roughness_level(const sp_library* library, const char* level, sp_material** out);
/* A named level of any percept with levels (calibration/levels/): ("softness", "soft") compiles
 * `softness soft`, a spring; ("slipperiness", "slippery") Coulomb friction. SP_ERROR_UNKNOWN_LEVEL
 * for a percept without levels or a level it does not define (sp_last_error() lists the known ones). */
sp_status sp_library_level(const sp_library* library, const char* percept, const char* level, sp_material** out);
void sp_material_free(sp_material* material);

/* The material's name, its maximum lateral force as compiled for the device (N), the ratio-scale
 * roughness the roughness map predicts for it (Minsky 1995, Fig. 19), and its warnings (one per
 * line, "" when none). NULL material: "" or 0. */
const char* sp_material_name(const sp_material* material);
double sp_material_compiled_max_lateral_force_N(const sp_material* material);
double sp_material_compiled_roughness(const sp_material* material);
const char* sp_material_warnings(const sp_material* material);

/* A player on the simulated joystick (calibration/devices/sim.toml): a scripted hand scanning
 * +-30 mm along x at 50 mm/s through the patch centre. */
sp_status sp_player_open_simulated(sp_player** out);
/* A player on the first USB HID PID force-feedback joystick plugged in whose IDs one of `library`'s
 * device calibrations names (docs/USB_PID.md). Compile its materials with a library opened for that
 * device: sp_player_device_calibration() names it. SP_ERROR_DEVICE when there is none or it cannot
 * be opened (sp_last_error() says why: for a permission problem, the udev rule to add). */
sp_status sp_player_open_usb(const sp_library* library, sp_player** out);
/* A player on a calibrated joystick found along the path `device` names (docs/DEVICES.md): "usb" (as
 * sp_player_open_usb), "hidraw" (its hidraw node, the kernel's driver left bound, no root needed) or
 * "hidraw:/dev/hidrawN". SP_ERROR_DEVICE as sp_player_open_usb, and for a device not on the bus;
 * SP_ERROR_ARGUMENT for a NULL argument. */
sp_status sp_player_open_device(const sp_library* library, const char* device, sp_player** out);
/* The same for an input event node no calibration file names ("evdev" or "evdev:/dev/input/eventN"):
 * it plays with the uncalibrated-evdev profile, its scale assumed and its force at most a quarter of
 * the device's strongest (docs/DEVICES.md); open the library for device "uncalibrated-evdev".
 * sp_player_warning() says so. SP_ERROR_DEVICE for any other path, and as sp_player_open_device. */
sp_status sp_player_open_device_uncalibrated(const sp_library* library, const char* device, sp_player** out);
/* What to tell a person before the player plays (a profile's assumed scale), or "". Owned by the player. */
const char* sp_player_warning(const sp_player* player);
/* The device calibration the player's materials must be compiled for ("openffboard-2axis"), or ""
 * for the simulated player (any material plays there). Owned by the player. */
const char* sp_player_device_calibration(const sp_player* player);
/* Stops the servo thread if it is still running, then frees the player. */
void sp_player_close(sp_player* player);

/* Plays `material` from the next start, or at once, crossfaded, if playing. */
sp_status sp_player_load(sp_player* player, const sp_material* material);
/* Starts the servo thread at rate_hz (900 - 10000 Hz, within the device's limits) for duration_s
 * seconds (0: until sp_player_stop). Returns at once. */
sp_status sp_player_start(sp_player* player, double rate_hz, double duration_s);
/* Stops at the next tick and waits for the servo thread; `report` may be NULL. */
sp_status sp_player_stop(sp_player* player, sp_report* report);
/* Waits for the run to end on its own (its duration, or a fault); `report` may be NULL. */
sp_status sp_player_wait(sp_player* player, sp_report* report);
/* 1 while the servo thread runs, else 0 (also for NULL). */
int sp_player_playing(const sp_player* player);

/* Records where an installed package's data lies (compiler/data_dirs.hpp): called before main by
 * sandpaper/package_location.h, which only an install has and which this header includes. */
void sp_register_package_data_dir(const char* header_file, const char* header_dir_to_data);

#ifdef __cplusplus
}
#endif

/* In an installed package: register where its data lies, found from where its headers lie. */
#if defined(__has_include)
#if __has_include(<sandpaper/package_location.h>)
#include <sandpaper/package_location.h>
#endif
#endif
#endif /* SANDPAPER_SANDPAPER_H */
