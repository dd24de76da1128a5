#pragma once
// An experiment design file (schema/files/experiment.schema.json, docs/EXPERIMENTS.md): the stimuli,
// the task, repetitions, the seeded shuffle, practice, breaks, instructions and how each stimulus is
// presented. The thesis' three procedures (Minsky 1995: 4.4 confidence, 5.2.3 magnitude estimation,
// 6.2.5 sorting) and a two-interval forced choice for force JNDs.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sandpaper::experiment {

// A design (or results folder) that cannot be used; what() holds one line per problem, each
// "file:line:col: error: message", so the experimenter sees every problem before the first trial.
struct DesignError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class Task { MagnitudeEstimation, Confidence, Sorting, TwoInterval };
// "magnitude-estimation", "confidence", "sorting", "two-interval".
const char* task_name(Task t) noexcept;

struct StimulusRef {
  std::string text;   // as written: a library or thesis name, or a material file's path
  std::filesystem::path file;  // set when `text` names a material file (resolved against the design's folder)
  int line = 0, column = 0;    // where it is written, for diagnostics
};

struct Design {
  std::string path;              // as given, for messages
  std::string text;              // the file's bytes, copied into every results folder
  std::string checksum;          // "fnv1a64:<16 hex digits>" of `text`: runs of one design pool together
  std::string title;              // the experimenter's ("... Minsky 1995 chapter 5")
  std::string subject_title;      // what the subject sees; empty: subject_title_of() picks one
  Task task = Task::MagnitudeEstimation;
  std::string device = "sim";
  // What a magnitude-estimation design scales (percept_quantity.hpp): "roughness" (the default),
  // "softness", "viscosity" or "slipperiness".
  std::string percept = "roughness";
  std::vector<StimulusRef> stimuli;
  int repetitions = 1;
  std::uint64_t seed = 0;
  int practice = 0;
  int break_every = 0;
  std::string instructions;
  // Presentation (SI): full-force time, ramp either side, servo rate; the scripted hand of the
  // simulated device scans at hand_speed_m_s, turning at +-hand_amplitude_m.
  double duration_s = 2.0, ramp_s = 0.25, rate_hz = 1000;
  double hand_speed_m_s = 0.05, hand_amplitude_m = 0.02;
  std::vector<int> piles;        // sorting: successive pile counts
  std::vector<double> increments;  // two-interval: comparison force = standard x (1 + increment)
};

// The heading the subject sees: the design's subject_title, else one for the task and percept
// ("Rate how rough each surface feels"), never the experimenter's title with its citation.
std::string subject_title_of(const Design& d);
// The instructions as paragraphs: a blank line ends one, a single line break inside one is a
// space (TOML's multi-line strings keep the author's hard breaks), surrounding blanks trimmed.
std::vector<std::string> instruction_paragraphs(const std::string& text);

// FNV-1a, 64 bit (Fowler, Noll, Vo): a stable hash of bytes, for checksums and seeds, not security.
std::uint64_t fnv1a64(std::string_view bytes) noexcept;
// fnv1a64 of the design's text as "fnv1a64:%016x": a checksum to tell designs apart.
std::string design_checksum(const std::string& text);

// Reads and validates a design. Throws DesignError listing every problem (schema violations,
// a task section missing or given to the wrong task, a material file that does not exist).
Design load_design(const std::filesystem::path& path);
// The same from text; `path` names the file in messages and anchors relative material paths.
Design parse_design(const std::string& text, const std::filesystem::path& path);

}  // namespace sandpaper::experiment
