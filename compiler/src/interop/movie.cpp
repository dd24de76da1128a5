#include "sandpaper/compiler/movie.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <chrono>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "sandpaper/compiler/shuffle.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/input_limits.hpp"

namespace sandpaper::compiler {
namespace {

namespace fs = std::filesystem;

// CRLF and lone CR (classic Macintosh text) become LF, so that lines and columns count as usual.
std::string normalise_line_ends(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\r') {
      out += '\n';
      if (i + 1 < text.size() && text[i + 1] == '\n') ++i;
    } else {
      out += text[i];
    }
  }
  return out;
}

std::optional<std::string> read_text(const fs::path& path) {
  try {
    return normalise_line_ends(schema::read_input_file(path, schema::limits::kMaxTextFileBytes));
  } catch (const schema::InputFileError&) {
    return std::nullopt;
  }
}

struct Line {
  int number = 0;
  std::string_view text;  // trimmed
  int column = 1;         // of the first non-blank character
};

std::vector<Line> lines_of(const SourceFile& f) {
  std::vector<Line> out;
  for (std::size_t i = 0; i < f.line_starts.size(); ++i) {
    const int number = static_cast<int>(i) + 1;
    std::string_view t = f.line_text(number);
    std::size_t b = 0;
    while (b < t.size() && std::isspace(static_cast<unsigned char>(t[b]))) ++b;
    std::size_t e = t.size();
    while (e > b && std::isspace(static_cast<unsigned char>(t[e - 1]))) --e;
    out.push_back({number, t.substr(b, e - b), static_cast<int>(b) + 1});
  }
  // The text after a final newline is not a line.
  if (!out.empty() && f.text.size() == f.line_starts.back()) out.pop_back();
  return out;
}

SourceLocation at(const std::shared_ptr<const SourceFile>& f, const Line& l) {
  return {f, l.number, l.column, std::max(1, static_cast<int>(l.text.size()))};
}

bool digits(std::string_view s, std::size_t b, std::size_t n) {
  if (b + n > s.size()) return false;
  for (std::size_t i = b; i < b + n; ++i)
    if (s[i] < '0' || s[i] > '9') return false;
  return true;
}
int number_at(std::string_view s, std::size_t b, std::size_t n) {
  int v = 0;
  std::from_chars(s.data() + b, s.data() + b + n, v);
  return v;
}

}  // namespace

std::optional<Movie> read_movie(const fs::path& path, Diagnostics& diags) {
  const auto text = read_text(path);
  if (!text) {
    auto f = std::make_shared<const SourceFile>(path.string(), "");
    diags.error("E0510", SourceLocation{f, 0, 0, 1}, "cannot open movie file '" + path.string() + "'",
                "check the path; a movie file lists workspace files, one a line");
    return std::nullopt;
  }
  auto file = std::make_shared<const SourceFile>(path.string(), *text);
  Movie movie;
  movie.path = path;
  Diagnostics local;
  const fs::path dir = path.parent_path();
  for (const Line& l : lines_of(*file)) {
    if (l.text.empty()) continue;
    const std::string name(l.text);
    if (movie.frames.size() == kMaxMovieFrames)
      local.error("E0511", at(file, l), "frame " + std::to_string(kMaxMovieFrames + 1) + ": a movie holds at most " +
                                             std::to_string(kMaxMovieFrames) + " frames (thesis Appendix B)",
                  "split the list into movies of at most " + std::to_string(kMaxMovieFrames) + " frames");
    std::error_code ec;
    if (!fs::is_regular_file(dir / name, ec))
      local.error("E0512", at(file, l), "no workspace file '" + name + "' beside the movie (looked for " + (dir / name).string() + ")",
                  "names are relative to the movie file's folder; check the spelling or create the workspace");
    movie.frames.push_back(name);
    movie.frame_locations.push_back(at(file, l));
  }
  if (movie.frames.empty())
    local.error("E0513", SourceLocation{file, 0, 0, 1}, "the movie '" + path.string() + "' has no frames",
                "list workspace files (.hws), one a line");
  diags.append(local);
  if (local.has_errors()) return std::nullopt;
  return movie;
}

std::string format_movie(const std::vector<std::string>& frames) {
  if (frames.size() > kMaxMovieFrames)
    throw std::invalid_argument("a movie holds at most " + std::to_string(kMaxMovieFrames) + " frames (thesis Appendix B), not " +
                                std::to_string(frames.size()));
  std::string out;
  for (const auto& name : frames) {
    if (name.empty() || name.find_first_of("\r\n") != std::string::npos || std::isspace(static_cast<unsigned char>(name.front())) ||
        std::isspace(static_cast<unsigned char>(name.back())))
      throw std::invalid_argument("movie frame name '" + name + "' is empty, has a line break, or starts or ends with a space");
    out += name + "\n";
  }
  return out;
}

void write_movie(const fs::path& path, const std::vector<std::string>& frames) {
  schema::write_file_atomically(path, format_movie(frames));
}

Shuffle shuffle_movie(const Movie& movie, std::uint64_t seed, std::string movie_name, std::string date, std::string time) {
  Shuffle s;
  s.movie = std::move(movie_name);
  s.date = std::move(date);
  s.time = std::move(time);
  for (std::size_t original : seeded_permutation(movie.frames.size(), seed))
    s.frames.push_back({original + 1, movie.frames[original]});
  return s;
}

std::string format_shuffle(const Shuffle& s) {
  std::string out = "Movie: " + s.movie + "\nDate: " + s.date + "\nTime: " + s.time + "\n\n";
  for (const auto& f : s.frames) out += std::to_string(f.original_index) + " " + f.name + "\n";
  return out;
}

std::optional<Shuffle> parse_shuffle(const std::shared_ptr<const SourceFile>& file, Diagnostics& diags) {
  Diagnostics local;
  Shuffle s;
  const std::vector<Line> lines = lines_of(*file);
  const auto header = [&](std::size_t i, std::string_view key, std::string& value) {
    const std::string expected = std::string(key) + ": ";
    if (i >= lines.size() || lines[i].text.substr(0, key.size() + 1) != std::string(key) + ":") {
      SourceLocation where = i < lines.size() ? at(file, lines[i]) : SourceLocation{file, 0, 0, 1};
      local.error("E0521", where, "line " + std::to_string(i + 1) + " of a shuffle file must be `" + expected + "...`",
                  "a shuffle starts with Movie:, Date: and Time: lines, then a blank line");
      return false;
    }
    std::string_view v = lines[i].text.substr(key.size() + 1);
    while (!v.empty() && std::isspace(static_cast<unsigned char>(v.front()))) v.remove_prefix(1);
    value = std::string(v);
    return true;
  };
  if (!header(0, "Movie", s.movie) || !header(1, "Date", s.date) || !header(2, "Time", s.time)) {
    diags.append(local);
    return std::nullopt;
  }
  if (lines.size() < 4 || !lines[3].text.empty()) {
    local.error("E0521", lines.size() >= 4 ? at(file, lines[3]) : SourceLocation{file, 0, 0, 1},
                "a blank line must follow the Movie:, Date: and Time: lines", "insert an empty line before the frames");
    diags.append(local);
    return std::nullopt;
  }
  std::vector<SourceLocation> where;
  for (std::size_t i = 4; i < lines.size(); ++i) {
    const Line& l = lines[i];
    if (l.text.empty()) continue;
    std::size_t n = 0;
    while (n < l.text.size() && l.text[n] >= '0' && l.text[n] <= '9') ++n;
    std::size_t b = n;
    while (b < l.text.size() && std::isspace(static_cast<unsigned char>(l.text[b]))) ++b;
    std::size_t index = 0;
    const auto [ptr, ec] = std::from_chars(l.text.data(), l.text.data() + n, index);
    if (n == 0 || b == n || b == l.text.size() || ec != std::errc() || ptr != l.text.data() + n) {
      local.error("E0522", at(file, l), "expected `<original index> <workspace name>`, found `" + std::string(l.text) + "`",
                  "each frame line is the frame's 1-based position in the original movie, a space, and its name");
      continue;
    }
    s.frames.push_back({index, std::string(l.text.substr(b))});
    where.push_back(at(file, l));
  }
  // The indices must be a permutation of 1..N.
  std::vector<std::size_t> first_line(s.frames.size() + 1, 0);
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    const std::size_t idx = s.frames[k].original_index;
    if (idx < 1 || idx > s.frames.size()) {
      local.error("E0523", where[k], "original index " + std::to_string(idx) + " is outside 1.." + std::to_string(s.frames.size()),
                  "indices number the movie's frames from 1");
    } else if (first_line[idx] != 0) {
      auto& d = local.error("E0523", where[k], "original index " + std::to_string(idx) + " appears twice",
                            "each frame of the movie appears once in its shuffle");
      d.notes.push_back({where[first_line[idx] - 1], "first here"});
    } else {
      first_line[idx] = k + 1;
    }
  }
  diags.append(local);
  if (local.has_errors()) return std::nullopt;
  return s;
}

std::optional<Shuffle> read_shuffle(const fs::path& path, Diagnostics& diags) {
  const auto text = read_text(path);
  if (!text) {
    auto f = std::make_shared<const SourceFile>(path.string(), "");
    diags.error("E0520", SourceLocation{f, 0, 0, 1}, "cannot open shuffle file '" + path.string() + "'", "check the path");
    return std::nullopt;
  }
  return parse_shuffle(std::make_shared<const SourceFile>(path.string(), *text), diags);
}

bool looks_like_shuffle(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  char head[6] = {};
  in.read(head, sizeof head);
  return in.gcount() == sizeof head && std::string_view(head, sizeof head) == "Movie:";
}

void check_shuffle_against_movie(const Shuffle& s, const Movie& movie, const SourceLocation& where, Diagnostics& diags) {
  if (s.frames.size() != movie.frames.size()) {
    diags.error("E0524", where,
                "the shuffle has " + std::to_string(s.frames.size()) + " frames but its movie '" + movie.path.string() + "' has " +
                    std::to_string(movie.frames.size()),
                "the movie changed after it was shuffled; shuffle it again");
    return;
  }
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    const auto& f = s.frames[k];
    if (f.original_index < 1 || f.original_index > movie.frames.size()) continue;  // E0523's business
    const std::string& expected = movie.frames[f.original_index - 1];
    if (f.name != expected)
      diags.error("E0524", where,
                  "shuffled frame " + std::to_string(k + 1) + " is '" + f.name + "', but frame " + std::to_string(f.original_index) +
                      " of the movie is '" + expected + "'",
                  "the movie changed after it was shuffled; shuffle it again");
  }
}

fs::path default_shuffle_path(const fs::path& movie, const std::string& date, const std::string& time) {
  const auto compact = [](const std::string& s, char sep) {
    std::string out;
    for (char c : s)
      if (c != sep) out += c;
    return out;
  };
  return movie.parent_path() / (movie.stem().string() + "-" + compact(date, '-') + "-" + compact(time, ':') + ".shuffle");
}

bool is_valid_date(const std::string& d) {
  if (d.size() != 10 || d[4] != '-' || d[7] != '-' || !digits(d, 0, 4) || !digits(d, 5, 2) || !digits(d, 8, 2)) return false;
  const int y = number_at(d, 0, 4), m = number_at(d, 5, 2), day = number_at(d, 8, 2);
  static const int days[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (m < 1 || m > 12 || day < 1 || day > days[m - 1]) return false;
  const bool leap = (y % 4 == 0 && y % 100 != 0) || y % 400 == 0;
  return !(m == 2 && day == 29 && !leap);
}

bool is_valid_time(const std::string& t) {
  if (t.size() != 8 || t[2] != ':' || t[5] != ':' || !digits(t, 0, 2) || !digits(t, 3, 2) || !digits(t, 6, 2)) return false;
  return number_at(t, 0, 2) <= 23 && number_at(t, 3, 2) <= 59 && number_at(t, 6, 2) <= 60;
}

void local_date_time_now(std::string& date, std::string& time) {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&now, &tm);
  char d[16], t[16];
  std::strftime(d, sizeof d, "%Y-%m-%d", &tm);
  std::strftime(t, sizeof t, "%H:%M:%S", &tm);
  date = d;
  time = t;
}

}  // namespace sandpaper::compiler
