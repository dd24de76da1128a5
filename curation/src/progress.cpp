#include "sandpaper/curation/progress.hpp"

#include <unistd.h>
#include <iostream>

namespace sandpaper::curation {

Progress::Progress(std::string verb, std::size_t total, bool quiet, std::ostream& out, bool terminal, std::size_t every)
    : verb_(std::move(verb)), total_(total), every_(every == 0 ? 1 : every), quiet_(quiet), terminal_(terminal), out_(&out) {}

Progress Progress::on_stderr(std::string verb, std::size_t total, bool quiet) {
  return Progress(std::move(verb), total, quiet, std::cerr, isatty(STDERR_FILENO) != 0);
}

void Progress::step(const std::string& name) {
  ++done_;
  if (quiet_) return;
  if (terminal_) {
    std::string line = verb_ + " " + std::to_string(done_) + "/" + std::to_string(total_) + " " + name;
    // Pad over a longer previous line so no tail of it is left on screen.
    std::string padded = line + std::string(last_width_ > line.size() ? last_width_ - line.size() : 0, ' ');
    *out_ << '\r' << padded << std::flush;
    last_width_ = line.size();
  } else if (done_ % every_ == 0 || done_ == total_) {
    *out_ << verb_ << " " << done_ << "/" << total_ << "\n" << std::flush;
  }
}

void Progress::clear() {
  if (quiet_) return;
  if (terminal_ && last_width_ > 0) *out_ << '\r' << std::string(last_width_, ' ') << '\r' << std::flush;
  last_width_ = 0;
}

void Progress::finish(const std::string& summary) {
  if (quiet_) return;
  clear();
  *out_ << summary << "\n" << std::flush;
}

}  // namespace sandpaper::curation
