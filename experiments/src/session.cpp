#include "sandpaper/experiment/session.hpp"

#include <chrono>
#include <ostream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "sandpaper/experiment/percept_quantity.hpp"

namespace sandpaper::experiment {
namespace {

struct Played {
  Presented presented;
  bool interrupted = false;
  std::string cause;
};

// Plays one stimulus into `out`; false when the loop stopped.
bool play(Presenter& presenter, const Stimulus& s, double gain, Played& out, std::vector<double>& quantity) {
  const Presentation p = presenter.present(s.program, gain);
  if (p.interrupted) {
    out.interrupted = true;
    out.cause = p.cause;
    return false;
  }
  out.presented.names.push_back(s.name);
  out.presented.felt_force_N.push_back(p.felt_max_N);
  out.presented.compiled_force_N.push_back(s.force_N * gain);
  out.presented.period_m.push_back(s.period_m);
  quantity.push_back(s.quantity);
  return true;
}

}  // namespace

SessionOutcome run_session(const Design& design, const std::vector<Stimulus>& stimuli,
                           const std::vector<Trial>& schedule, int first_trial, Presenter& presenter,
                           Observer& observer, ResultsWriter& writer, std::ostream& log) {
  SessionOutcome out;
  out.total = static_cast<int>(schedule.size());
  out.next_trial = first_trial;
  observer.instructions(subject_title_of(design), design.instructions);
  int main_done = 0;
  for (const auto& t : schedule)
    if (!t.practice && t.index < first_trial) ++main_done;
  for (int i = first_trial; i < out.total; ++i) {
    const Trial& t = schedule[static_cast<std::size_t>(i)];
    observer.announce(t, out.total);
    Played played;
    played.presented.percept = design.percept;
    std::vector<double> quantity;
    bool ok = true;
    if (design.task == Task::TwoInterval) {
      const Stimulus& s = stimuli[static_cast<std::size_t>(t.stimuli.at(0))];
      for (int interval = 1; ok && interval <= 2; ++interval)
        ok = play(presenter, s, interval == t.comparison_interval ? 1.0 + t.increment : 1.0, played, quantity);
    } else {
      for (int k : t.stimuli) {
        ok = play(presenter, stimuli[static_cast<std::size_t>(k)], 1.0, played, quantity);
        if (!ok) break;
      }
    }
    if (!ok) {
      writer.append({{"record", "interrupted"}, {"trial", t.index}, {"cause", played.cause}, {"time", utc_now_iso()}});
      // Only a device fault needs mending; a stop asked for (Ctrl-C) does not.
      const bool asked = played.cause == "stop_requested";
      log << fmt::format("trial {} of {} interrupted: {}; the force is off. {}`sandpaper experiment resume` continues "
                         "from this trial.\n",
                         t.index + 1, out.total, asked ? "stopped as asked" : "the loop stopped (" + played.cause + ")",
                         asked ? "" : "Fix the device, then ");
      out.interrupted = true;
      out.cause = played.cause;
      observer.ended(false);
      return out;
    }
    const auto asked = std::chrono::steady_clock::now();
    Answer a;
    a.trial = t.index;
    a.practice = t.practice;
    a.repetition = t.repetition;
    a.stimuli = played.presented.names;
    a.compiled_force_N = played.presented.compiled_force_N;
    a.felt_force_N = played.presented.felt_force_N;
    a.period_m = played.presented.period_m;
    if (const auto* q = find_percept_quantity(design.percept); q && design.percept != "roughness") {
      a.quantity_key = q->results_key;
      a.quantity = quantity;
    }
    bool answered = true;
    switch (design.task) {
      case Task::MagnitudeEstimation:
      case Task::Confidence: {
        auto v = observer.estimate(t, played.presented, design.task == Task::Confidence);
        answered = v.has_value();
        a.response = v;
        break;
      }
      case Task::TwoInterval: {
        auto c = observer.choose_interval(t, played.presented);
        answered = c.has_value();
        a.increment = t.increment;
        a.comparison_interval = t.comparison_interval;
        a.chosen_interval = c.value_or(0);
        a.correct = a.chosen_interval == t.comparison_interval;
        break;
      }
      case Task::Sorting: {
        auto labels = observer.sort(t, played.presented, t.piles);
        answered = labels.has_value();
        if (labels) {
          a.piles.assign(static_cast<std::size_t>(t.piles), {});
          for (std::size_t k = 0; k < labels->size(); ++k)
            a.piles[static_cast<std::size_t>((*labels)[k])].push_back(played.presented.names[k]);
        }
        break;
      }
    }
    if (!answered) {
      out.stopped = true;
      log << fmt::format("stopped at trial {} of {}; `sandpaper experiment resume` continues there\n", t.index + 1,
                         out.total);
      observer.ended(false);
      return out;
    }
    a.rt_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
    a.time = utc_now_iso();
    writer.append(to_json(a));
    ++out.answered;
    out.next_trial = i + 1;
    log << fmt::format("trial {:>3} of {}{}: {} felt {:.3f} N{}\n", t.index + 1, out.total, t.practice ? " (practice)" : "",
                       fmt::join(a.stimuli.size() > 3 ? std::vector<std::string>{a.stimuli.front(), "..."} : a.stimuli, ", "),
                       a.felt_force_N.front(),
                       a.response ? fmt::format(" -> {:g}", *a.response)
                       : a.comparison_interval ? fmt::format(" -> interval {} ({})", a.chosen_interval, a.correct ? "correct" : "wrong")
                                               : fmt::format(" -> {} piles", a.piles.size()));
    if (!t.practice) ++main_done;
    if (design.break_every > 0 && !t.practice && main_done % design.break_every == 0 && i + 1 < out.total)
      observer.rest(i + 1, out.total);
  }
  out.finished = true;
  observer.ended(true);
  return out;
}

}  // namespace sandpaper::experiment
