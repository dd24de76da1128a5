#pragma once
// Progress of a long run over the library's entries (check, index), on stderr: a `\r` counter when
// the stream is a terminal, else one line every `every` entries; a final summary line either way.
#include <cstddef>
#include <ostream>
#include <string>

namespace sandpaper::curation {

class Progress {
 public:
  // `verb` heads each line ("checking", "indexing"); `total` entries; nothing is printed when `quiet`.
  Progress(std::string verb, std::size_t total, bool quiet, std::ostream& out, bool terminal, std::size_t every = 10);
  // Progress on std::cerr, as a terminal if stderr is one.
  static Progress on_stderr(std::string verb, std::size_t total, bool quiet);
  // How many entries there are to do, once known (an incremental build knows only after its scan).
  void set_total(std::size_t total) { total_ = total; }
  // One more entry done; `name` is shown on a terminal.
  void step(const std::string& name);
  // Takes a terminal's counter off its line, so that what is printed next starts a line of its own.
  void clear();
  // Ends the counter and prints `summary` on its own line (unless quiet).
  void finish(const std::string& summary);
  std::size_t done() const { return done_; }

 private:
  std::string verb_;
  std::size_t total_, every_, done_ = 0;
  bool quiet_, terminal_;
  std::ostream* out_;
  std::size_t last_width_ = 0;
};

}  // namespace sandpaper::curation
