#include "sandpaper/experiment/results.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <chrono>
#include <cstring>
#include <optional>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::experiment {
namespace {

constexpr const char* kResultsFile = "results.jsonl";
constexpr const char* kDesignCopy = "design.toml";

std::string read_all(const std::filesystem::path& p) {
  try {
    return schema::read_input_file(p, schema::limits::kMaxTextFileBytes);
  } catch (const schema::InputFileError& e) {
    throw DesignError(p.string() + ": error: cannot read (" + e.reason +
                      "; is this a results folder of `sandpaper experiment run`?)");
  }
}

template <class T>
std::vector<T> vec(const nlohmann::json& j, const char* key) {
  std::vector<T> out;
  if (j.contains(key)) out = j.at(key).get<std::vector<T>>();
  return out;
}

// A whole number that fits an int, or `fallback` when the key is absent (no fallback: required).
// nlohmann's get<int> of 2.2e100 or 1.5 is undefined behaviour: refuse instead.
int whole(const nlohmann::json& j, const char* key, std::optional<int> fallback = std::nullopt) {
  if (!j.contains(key)) {
    if (fallback) return *fallback;
    throw std::invalid_argument(std::string("no `") + key + "`");
  }
  const auto& v = j.at(key);
  if (v.is_number_unsigned() && v.get<std::uint64_t>() <= static_cast<std::uint64_t>(INT_MAX))
    return static_cast<int>(v.get<std::uint64_t>());
  if (v.is_number_integer() && !v.is_number_unsigned() && v.get<std::int64_t>() >= INT_MIN && v.get<std::int64_t>() <= INT_MAX)
    return static_cast<int>(v.get<std::int64_t>());
  throw std::invalid_argument(std::string("`") + key + "` must be a whole number from " + std::to_string(INT_MIN) +
                              " to " + std::to_string(INT_MAX));
}

Answer answer_from(const nlohmann::json& j) {
  Answer a;
  a.trial = whole(j, "trial");
  a.practice = j.value("practice", false);
  a.repetition = whole(j, "repetition", 0);
  a.stimuli = vec<std::string>(j, "stimuli");
  a.compiled_force_N = vec<double>(j, "compiled_force_N");
  a.felt_force_N = vec<double>(j, "felt_force_N");
  a.period_m = vec<double>(j, "period_m");
  for (const char* key : {"stiffness_N_per_m", "damping_N_s_per_m", "friction_coefficient"})
    if (j.contains(key)) {
      a.quantity_key = key;
      a.quantity = vec<double>(j, key);
      if (a.quantity.size() != a.stimuli.size()) throw std::invalid_argument(std::string(key) + " and stimuli differ in length");
    }
  if (j.contains("response") && !j.at("response").is_null()) a.response = j.at("response").get<double>();
  a.increment = j.value("increment", 0.0);
  a.comparison_interval = whole(j, "comparison_interval", 0);
  a.chosen_interval = whole(j, "chosen_interval", 0);
  a.correct = j.value("correct", false);
  if (j.contains("piles")) a.piles = j.at("piles").get<std::vector<std::vector<std::string>>>();
  a.rt_s = j.value("rt_s", 0.0);
  a.time = j.value("time", std::string());
  if (a.stimuli.size() != a.compiled_force_N.size() || a.stimuli.size() != a.felt_force_N.size() ||
      a.stimuli.size() != a.period_m.size())
    throw std::invalid_argument("stimuli, compiled_force_N, felt_force_N and period_m differ in length");
  return a;
}

}  // namespace

int Results::next_trial() const {
  int next = 0;
  for (const auto& a : answers)
    if (a.trial == next) ++next;
  return next;
}

nlohmann::json to_json(const Answer& a) {
  nlohmann::json j{{"record", "answer"},         {"trial", a.trial},
                   {"practice", a.practice},     {"repetition", a.repetition},
                   {"stimuli", a.stimuli},       {"compiled_force_N", a.compiled_force_N},
                   {"felt_force_N", a.felt_force_N}, {"period_m", a.period_m}};
  if (!a.quantity_key.empty()) j[a.quantity_key] = a.quantity;
  if (a.response) j["response"] = *a.response;
  if (a.comparison_interval) {
    j["increment"] = a.increment;
    j["comparison_interval"] = a.comparison_interval;
    j["chosen_interval"] = a.chosen_interval;
    j["correct"] = a.correct;
  }
  if (!a.piles.empty()) j["piles"] = a.piles;
  j["rt_s"] = a.rt_s;
  j["time"] = a.time;
  return j;
}

nlohmann::json to_json(const ResultsHeader& h) {
  return {{"record", "header"},      {"format", kResultsFormat}, {"design_checksum", h.design_checksum},
          {"design", h.design_path}, {"subject", h.subject},     {"task", h.task},
          {"device", h.device},      {"observer", h.observer},   {"started", h.started},
          {"trials", h.trials},      {"percept", h.percept}};
}

Results read_results(const std::filesystem::path& dir) {
  Results r;
  r.dir = dir;
  const auto file = dir / kResultsFile;
  r.design_text = read_all(dir / kDesignCopy);
  const std::string text = read_all(file);
  std::istringstream in(text);
  std::string line;
  int n = 0;
  bool header = false;
  std::size_t consumed = 0;
  while (std::getline(in, line)) {
    ++n;
    consumed += line.size() + 1;
    const bool torn = consumed > text.size();  // the last line has no newline: written when killed
    if (line.empty()) continue;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
      const std::string kind = j.at("record").get<std::string>();
      if (kind == "header") {
        if (j.value("format", "") != kResultsFormat)
          throw std::invalid_argument(std::string("format is not ") + kResultsFormat);
        r.header.design_checksum = j.at("design_checksum").get<std::string>();
        r.header.design_path = j.value("design", "");
        r.header.subject = j.at("subject").get<std::string>();
        r.header.task = j.at("task").get<std::string>();
        r.header.percept = j.value("percept", std::string("roughness"));
        r.header.device = j.value("device", "");
        r.header.observer = j.value("observer", "");
        r.header.started = j.value("started", "");
        r.header.trials = whole(j, "trials");
        header = true;
      } else if (kind == "answer") {
        r.answers.push_back(answer_from(j));
      } else if (kind == "interrupted") {
        r.interruptions.push_back({whole(j, "trial"), j.value("cause", "")});
      } else if (kind == "observer-switch") {
        r.observer_switches.push_back({j.at("from").get<std::string>(), j.at("to").get<std::string>(), whole(j, "trial")});
      } else {
        throw std::invalid_argument("unknown record `" + kind + "`");
      }
    } catch (const std::exception& e) {
      if (torn) break;
      throw DesignError(file.string() + ":" + std::to_string(n) + ":1: error: malformed record: " + e.what());
    }
  }
  if (!header) throw DesignError(file.string() + ":1:1: error: no header record; this is not a results file");
  if (design_checksum(r.design_text) != r.header.design_checksum)
    throw DesignError((dir / kDesignCopy).string() + ": error: the design was changed after the run started (checksum " +
                      design_checksum(r.design_text) + ", results say " + r.header.design_checksum +
                      "); restore it, or start a new results folder");
  return r;
}

ResultsWriter ResultsWriter::create(const std::filesystem::path& dir, const Design& design, const ResultsHeader& header) {
  std::filesystem::create_directories(dir);
  if (std::filesystem::exists(dir / kResultsFile))
    throw DesignError((dir / kResultsFile).string() + ": error: this folder already holds results; continue them with "
                      "`sandpaper experiment resume " + dir.string() + "`, or give another -o folder");
  schema::write_file_atomically(dir / kDesignCopy, design.text);
  const int fd = ::open((dir / kResultsFile).c_str(), O_WRONLY | O_CREAT | O_EXCL | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error((dir / kResultsFile).string() + ": cannot create: " + std::strerror(errno));
  ResultsWriter w(fd, dir / kResultsFile);
  w.append(to_json(header));
  return w;
}

ResultsWriter ResultsWriter::reopen(const std::filesystem::path& dir) {
  const auto path = dir / kResultsFile;
  const std::string text = read_all(path);
  const auto keep = text.rfind('\n');
  const auto length = keep == std::string::npos ? 0 : keep + 1;
  if (length != text.size()) std::filesystem::resize_file(path, length);  // the torn trial in progress
  const int fd = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(path.string() + ": cannot open to append: " + std::strerror(errno));
  return ResultsWriter(fd, path);
}

ResultsWriter::ResultsWriter(ResultsWriter&& o) noexcept : fd_(o.fd_), path_(std::move(o.path_)) { o.fd_ = -1; }

ResultsWriter::~ResultsWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void ResultsWriter::append(const nlohmann::json& record) {
  // One write() of the whole line: with O_APPEND a crash leaves either the line or a torn tail.
  // Bytes that are not UTF-8 (a subject id, a path) become U+FFFD rather than losing the record.
  const std::string line = record.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t k = ::write(fd_, line.data() + done, line.size() - done);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) throw std::runtime_error(path_.string() + ": cannot append: " + std::strerror(errno));
    done += static_cast<std::size_t>(k);
  }
  if (::fdatasync(fd_) != 0) throw std::runtime_error(path_.string() + ": cannot flush to disk: " + std::strerror(errno));
}

std::string utc_now_iso() {
  const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace sandpaper::experiment
