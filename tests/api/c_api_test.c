/* The C API (sandpaper/sandpaper.h) from a C program, as an engine plug-in would call it: compile by
 * name and by text, errors as status codes with messages, play and stop on the simulated joystick.
 * Built as C11 (tests/api/CMakeLists.txt, ctest api.c); prints each failed check and a count. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sandpaper/sandpaper.h"

static int checks, failures;

#define CHECK(cond, ...)                                       \
  do {                                                         \
    ++checks;                                                  \
    if (!(cond)) {                                             \
      ++failures;                                              \
      fprintf(stderr, "%s:%d: failed: %s: ", __FILE__, __LINE__, #cond); \
      fprintf(stderr, __VA_ARGS__);                            \
      fputc('\n', stderr);                                     \
    }                                                          \
  } while (0)

static int contains(const char* text, const char* part) { return text && strstr(text, part) != NULL; }

int main(void) {
  sp_library* lib = NULL;
  sp_material* corduroy = NULL;
  sp_material* coarse = NULL;
  sp_material* soft = NULL;
  sp_material* grating = NULL;
  sp_material* untouched = (sp_material*)&checks; /* a failed call must leave out-parameters alone */
  sp_player* player = NULL;
  sp_report report;

  CHECK(strcmp(sp_version(), "") != 0, "no version");
  CHECK(sp_library_open(NULL, NULL, NULL, &lib) == SP_OK, "%s", sp_last_error());
  if (!lib) return 1;

  CHECK(sp_library_compile(lib, "corduroy", &corduroy) == SP_OK, "%s", sp_last_error());
  CHECK(strcmp(sp_material_name(corduroy), "corduroy") == 0, "name %s", sp_material_name(corduroy));
  CHECK(sp_material_compiled_max_lateral_force_N(corduroy) > 0.0, "force %g", sp_material_compiled_max_lateral_force_N(corduroy));
  CHECK(sp_material_compiled_roughness(corduroy) > 0.0, "roughness %g", sp_material_compiled_roughness(corduroy));

  CHECK(sp_library_compile(lib, "grating period 2.5 mm hill 50% amplitude 0.8 N", &grating) == SP_OK, "%s", sp_last_error());
  CHECK(sp_library_roughness_level(lib, "coarse", &coarse) == SP_OK, "%s", sp_last_error());
  CHECK(sp_material_compiled_roughness(coarse) > 0.0, "coarse roughness %g", sp_material_compiled_roughness(coarse));
  CHECK(sp_library_level(lib, "softness", "soft", &soft) == SP_OK, "%s", sp_last_error());
  CHECK(contains(sp_material_warnings(soft), "W0321") && contains(sp_material_warnings(soft), "harper-stevens1964"),
        "a softness level names its map: %s", sp_material_warnings(soft));
  CHECK(sp_library_level(lib, "slipperiness", "slipery", &untouched) == SP_ERROR_UNKNOWN_LEVEL, "%s", sp_last_error());
  CHECK(contains(sp_last_error(), "did you mean \"slippery\""), "%s", sp_last_error());
  /* A percept with no levels is the unknown part; the percepts with levels are calibration/levels/'s four files. */
  CHECK(sp_library_level(lib, "softnes", "soft", &untouched) == SP_ERROR_UNKNOWN_LEVEL, "%s", sp_last_error());
  CHECK(contains(sp_last_error(), "unknown percept \"softnes\"") && contains(sp_last_error(), "roughness") &&
            contains(sp_last_error(), "slipperiness") && contains(sp_last_error(), "softness") &&
            contains(sp_last_error(), "viscosity") && contains(sp_last_error(), "did you mean \"softness\""),
        "the unknown percept not named with the ones that have levels: %s", sp_last_error());

  /* Errors: a status, a message that says how to fix it, and out-parameters untouched. */
  CHECK(sp_library_compile(lib, "grating period 2.5 parsecs", &untouched) == SP_ERROR_COMPILE, "%s", sp_last_error());
  CHECK(contains(sp_last_error(), "<compile>:1:") && contains(sp_last_error(), "^"),
        "diagnostics not file:line:col with a caret: %s", sp_last_error());
  CHECK(untouched == (sp_material*)&checks, "out-parameter changed by a failed compile");
  CHECK(sp_library_roughness_level(lib, "coarsee", &untouched) == SP_ERROR_UNKNOWN_LEVEL, "%s", sp_last_error());
  CHECK(contains(sp_last_error(), "did you mean \"coarse\""), "%s", sp_last_error());
  CHECK(sp_library_compile(NULL, "corduroy", &untouched) == SP_ERROR_ARGUMENT, "NULL library accepted");
  CHECK(contains(sp_last_error(), "`library` is NULL"), "%s", sp_last_error());
  CHECK(sp_library_open("/nonexistent/sandpaper-library", "/nonexistent/sandpaper-calibration", NULL,
                        (sp_library**)&untouched) == SP_ERROR_DATA, "missing directories accepted");
  CHECK(contains(sp_last_error(), "/nonexistent/sandpaper-library") &&
            contains(sp_last_error(), "/nonexistent/sandpaper-calibration"),
        "not every missing directory named: %s", sp_last_error());
  /* A C caller never wrote a C++ type: the message names none (no `Options`, no `::`, no `{`). */
  CHECK(!contains(sp_last_error(), "Options") && !contains(sp_last_error(), "::") && !contains(sp_last_error(), "{"),
        "the message names C++: %s", sp_last_error());
  CHECK(sp_library_open(NULL, NULL, "no-such-device", (sp_library**)&untouched) == SP_ERROR_DATA, "unknown device accepted");

  /* Playing: state errors, then a timed run and a run stopped from here. */
  CHECK(sp_player_open_simulated(&player) == SP_OK, "%s", sp_last_error());
  CHECK(strcmp(sp_player_device_calibration(player), "") == 0, "the simulated player plays any material");

  /* USB: a joystick the calibration knows opens; without one (CI, this sandbox) the error names
   * the joysticks it knows and leaves the out-parameter alone. */
  {
    sp_player* usb = (sp_player*)&checks;
    const sp_status st = sp_player_open_usb(lib, &usb);
    if (st == SP_OK) {
      CHECK(strcmp(sp_player_device_calibration(usb), "") != 0, "a USB player without its device calibration");
      sp_player_close(usb);
    } else {
      CHECK(st == SP_ERROR_DEVICE, "sp_player_open_usb: status %d: %s", (int)st, sp_last_error());
      CHECK(contains(sp_last_error(), "openffboard-2axis (1209:ffb0)"), "%s", sp_last_error());
      CHECK(usb == (sp_player*)&checks, "out-parameter changed by a failed open");
    }
    CHECK(sp_player_open_usb(NULL, &usb) == SP_ERROR_ARGUMENT, "NULL library accepted");
    /* Along a named path: a hidraw node that is not there is named in the error. */
    CHECK(sp_player_open_device(lib, "hidraw:/nonexistent/hidraw9", &usb) == SP_ERROR_DEVICE, "a missing node opened");
    CHECK(contains(sp_last_error(), "no hidraw node /nonexistent/hidraw9"), "%s", sp_last_error());
    CHECK(usb == (sp_player*)&checks, "out-parameter changed by a failed open");
    CHECK(sp_player_open_device(lib, NULL, &usb) == SP_ERROR_ARGUMENT, "NULL device accepted");
    /* Uncalibrated: an input event node alone; through hidraw it is refused, not ignored. */
    CHECK(sp_player_open_device_uncalibrated(lib, "hidraw", &usb) == SP_ERROR_DEVICE, "uncalibrated taken through hidraw");
    CHECK(contains(sp_last_error(), "--uncalibrated plays an input event node"), "%s", sp_last_error());
    CHECK(sp_player_open_device_uncalibrated(lib, "evdev:/nonexistent/event99", &usb) == SP_ERROR_DEVICE,
          "a missing event node opened");
    CHECK(contains(sp_last_error(), "/nonexistent/event99"), "%s", sp_last_error());
    CHECK(usb == (sp_player*)&checks, "out-parameter changed by a failed open");
    CHECK(sp_player_open_device_uncalibrated(lib, NULL, &usb) == SP_ERROR_ARGUMENT, "NULL device accepted");
  }
  CHECK(strcmp(sp_player_warning(player), "") == 0, "the simulated player warns: %s", sp_player_warning(player));
  CHECK(strcmp(sp_player_warning(NULL), "") == 0, "a NULL player warns");
  CHECK(sp_player_start(player, 1000.0, 0.3) == SP_ERROR_STATE, "start with nothing loaded");
  CHECK(sp_player_wait(player, &report) == SP_ERROR_STATE, "wait before start");
  CHECK(sp_player_load(player, corduroy) == SP_OK, "%s", sp_last_error());
  CHECK(sp_player_start(player, 50.0, 0.3) == SP_ERROR_ARGUMENT, "a 50 Hz servo rate accepted");
  CHECK(contains(sp_last_error(), "Hz"), "%s", sp_last_error());
  CHECK(sp_player_start(player, 1000.0, 0.3) == SP_OK, "%s", sp_last_error());
  CHECK(sp_player_start(player, 1000.0, 0.3) == SP_ERROR_STATE || !sp_player_playing(player), "second start while playing");
  memset(&report, 0, sizeof report);
  CHECK(sp_player_wait(player, &report) == SP_OK, "%s", sp_last_error());
  CHECK(report.ticks == 300, "ticks %llu", (unsigned long long)report.ticks);
  CHECK(report.stop_cause == 0 && strcmp(report.stop_cause_name, "completed") == 0, "stop %s", report.stop_cause_name);
  CHECK(report.felt_max_lateral_force_N > 0.0, "no force played");
  CHECK(report.felt_max_lateral_force_N <= sp_material_compiled_max_lateral_force_N(corduroy) * (1 + 1e-9),
        "played %g N above the compiled %g N", report.felt_max_lateral_force_N, sp_material_compiled_max_lateral_force_N(corduroy));
  CHECK(!sp_player_playing(player), "still playing after wait");

  /* Until stopped: the material freed while playing stays alive inside the player. */
  CHECK(sp_player_load(player, grating) == SP_OK, "%s", sp_last_error());
  sp_material_free(grating);
  CHECK(sp_player_start(player, 1000.0, 0.0) == SP_OK, "%s", sp_last_error());
  CHECK(sp_player_playing(player), "not playing after start");
  CHECK(sp_player_load(player, coarse) == SP_OK, "swap while playing: %s", sp_last_error());
  memset(&report, 0, sizeof report);
  CHECK(sp_player_stop(player, &report) == SP_OK, "%s", sp_last_error());
  CHECK(strcmp(report.stop_cause_name, "stop_requested") == 0, "stop %s", report.stop_cause_name);
  CHECK(sp_player_stop(player, NULL) == SP_ERROR_STATE, "stop twice");

  sp_player_close(player);
  sp_material_free(corduroy);
  sp_material_free(coarse);
  sp_material_free(soft);
  sp_library_close(lib);
  sp_player_close(NULL);
  sp_material_free(NULL);
  sp_library_close(NULL);
  CHECK(strcmp(sp_material_name(NULL), "") == 0 && sp_material_compiled_max_lateral_force_N(NULL) == 0.0, "NULL material");

  printf("c api: %d checks, %d failed\n", checks, failures);
  return failures ? 1 : 0;
}
