#pragma once
// A subject's results folder (docs/EXPERIMENTS.md, "Results"): design.toml, a byte-for-byte copy of
// the design that was run, and results.jsonl, one JSON object per line: a header, then one record
// per answered (or interrupted) trial, and one per deliberate change of observer on resuming. Each record is appended and flushed to disk (fdatasync)
// before the next trial starts, so `kill -9` loses at most the trial in progress; a torn last
// line is ignored on reading and cut off when the session resumes.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sandpaper/experiment/design.hpp"

namespace sandpaper::experiment {

inline constexpr const char* kResultsFormat = "sandpaper-experiment-results/1";

struct ResultsHeader {
  std::string design_checksum;   // Design::checksum of design.toml
  std::string design_path;       // the design as it was given to `run`
  std::string subject, task, device, observer;
  std::string percept = "roughness";  // the design's percept (absent in older results: roughness)
  std::string started;           // ISO 8601, UTC
  int trials = 0;                // in the schedule, practice included
};

// One presented trial. Forces N, periods m, times s.
struct Answer {
  int trial = 0;
  bool practice = false;
  int repetition = 0;
  std::vector<std::string> stimuli;          // presentation order
  std::vector<double> compiled_force_N;      // per stimulus: the compiled maximum lateral force (x gain)
  std::vector<double> felt_force_N;          // per stimulus: the largest |F| the loop actually wrote
  std::vector<double> period_m;
  // Per stimulus, a percept other than roughness: the physical quantity it is scaled on, SI, written
  // under its own key (percept_quantity.hpp: "stiffness_N_per_m", ...). Empty for roughness.
  std::string quantity_key;
  std::vector<double> quantity;
  std::optional<double> response;            // magnitude estimate (> 0) or confidence (0-100 %)
  double increment = 0;                      // two-interval
  int comparison_interval = 0, chosen_interval = 0;
  bool correct = false;
  std::vector<std::vector<std::string>> piles;  // sorting: stimulus names per pile
  double rt_s = 0;                           // from the end of the presentation to the answer
  std::string time;                          // ISO 8601, UTC, when answered
};

struct Interruption {
  int trial = 0;
  std::string cause;                         // runtime::stop_cause_name
};

// `experiment resume --switch-observer`: from this trial on, `to` answered instead of `from`.
struct ObserverSwitch {
  std::string from, to;
  int trial = 0;
};

struct Results {
  std::filesystem::path dir;
  std::string design_text;                   // design.toml
  ResultsHeader header;
  std::vector<Answer> answers;               // in file order
  std::vector<Interruption> interruptions;
  std::vector<ObserverSwitch> observer_switches;
  // The observer answering now: the header's, or the last switch's.
  std::string current_observer() const { return observer_switches.empty() ? header.observer : observer_switches.back().to; }
  // The first trial index with no answer (trials are answered in order); header.trials when done.
  int next_trial() const;
};

nlohmann::json to_json(const Answer& a);
nlohmann::json to_json(const ResultsHeader& h);

// Reads a results folder. Throws DesignError (file:line) for a missing file, a malformed line
// other than a torn last one, or a header whose checksum does not match design.toml.
Results read_results(const std::filesystem::path& dir);

// Appends records to results.jsonl, each flushed to disk before append() returns.
class ResultsWriter {
 public:
  // A new folder (created if missing): writes design.toml and the header. Throws DesignError if the
  // folder already holds results (resume it, or choose another folder).
  static ResultsWriter create(const std::filesystem::path& dir, const Design& design, const ResultsHeader& header);
  // An existing folder, to resume: cuts a torn last line off, then appends after it.
  static ResultsWriter reopen(const std::filesystem::path& dir);
  ResultsWriter(ResultsWriter&&) noexcept;
  ResultsWriter& operator=(ResultsWriter&&) = delete;
  ~ResultsWriter();

  // Throws std::runtime_error if the write or the flush fails (the disk is full, ...).
  void append(const nlohmann::json& record);

 private:
  explicit ResultsWriter(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)) {}
  int fd_ = -1;
  std::filesystem::path path_;
};

// "2026-11-22T01:23:45Z"
std::string utc_now_iso();

}  // namespace sandpaper::experiment
