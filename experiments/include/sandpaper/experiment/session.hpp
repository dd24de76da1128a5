#pragma once
// One subject's session: trials in schedule order from `first_trial`, each presented, answered and
// appended to the results file (flushed) before the next starts. A fault stops the force (the loop
// does that), records the trial as interrupted, never as answered, and ends the session so it can
// be resumed; so does the subject typing q.
#include <iosfwd>
#include <string>
#include <vector>

#include "sandpaper/experiment/design.hpp"
#include "sandpaper/experiment/observer.hpp"
#include "sandpaper/experiment/presenter.hpp"
#include "sandpaper/experiment/results.hpp"
#include "sandpaper/experiment/schedule.hpp"
#include "sandpaper/experiment/stimuli.hpp"

namespace sandpaper::experiment {

struct SessionOutcome {
  int answered = 0;          // trials answered in this session
  int next_trial = 0;        // the first unanswered trial afterwards
  int total = 0;             // trials in the schedule
  bool finished = false;     // every trial answered
  bool stopped = false;      // the subject stopped (q or end of input)
  bool interrupted = false;  // a device fault stopped the loop
  std::string cause;         // its stop cause name
};

// `log`: one progress line per trial (the experimenter's view; stderr). Throws what the results
// writer throws (a full disk): the answer not yet on disk is then the trial in progress.
SessionOutcome run_session(const Design& design, const std::vector<Stimulus>& stimuli,
                           const std::vector<Trial>& schedule, int first_trial, Presenter& presenter,
                           Observer& observer, ResultsWriter& writer, std::ostream& log);

}  // namespace sandpaper::experiment
