// `sandpaper movie shuffle|show`: movie and shuffle files (thesis Appendix B).
#include <iostream>

#include <fmt/format.h>

#include "cli.hpp"
#include "sandpaper/compiler/movie.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::cli {
namespace {

namespace fs = std::filesystem;

// The movie's path as seen from the folder the shuffle file is written to.
std::string movie_name_from(const fs::path& movie, const fs::path& shuffle) {
  const fs::path from = fs::absolute(shuffle).parent_path().lexically_normal();
  const fs::path rel = fs::absolute(movie).lexically_normal().lexically_relative(from);
  return rel.empty() ? movie.string() : rel.generic_string();
}

}  // namespace

int cmd_movie_shuffle(const MovieShuffleOptions& m, bool json) {
  std::string date = m.date, time = m.time;
  if ((date.empty() || time.empty())) {
    std::string now_date, now_time;
    compiler::local_date_time_now(now_date, now_time);
    if (date.empty()) date = now_date;
    if (time.empty()) time = now_time;
  }
  if (!compiler::is_valid_date(date)) {
    std::cerr << "sandpaper: error: --date '" << date << "' is not a date of the form YYYY-MM-DD\n";
    return kExitUsage;
  }
  if (!compiler::is_valid_time(time)) {
    std::cerr << "sandpaper: error: --time '" << time << "' is not a time of the form HH:MM:SS (24-hour)\n";
    return kExitUsage;
  }
  compiler::Diagnostics diags;
  auto movie = compiler::read_movie(m.movie, diags);
  std::cerr << compiler::format_diagnostics(diags);
  if (!movie) {
    if (json)
      std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(diags)}}, 2)
                << "\n";
    return kExitBadInput;
  }
  const fs::path out = m.output.empty() ? compiler::default_shuffle_path(m.movie, date, time) : fs::path(m.output);
  const auto shuffle = compiler::shuffle_movie(*movie, m.seed, movie_name_from(m.movie, out), date, time);
  schema::write_file_atomically(out, compiler::format_shuffle(shuffle));
  if (json) {
    nlohmann::json frames = nlohmann::json::array();
    for (const auto& f : shuffle.frames) frames.push_back({{"original_index", f.original_index}, {"name", f.name}});
    std::cout << schema::json_text(nlohmann::json{{"ok", true},
                                                  {"movie", shuffle.movie},
                                                  {"date", date},
                                                  {"time", time},
                                                  {"seed", m.seed},
                                                  {"frames", frames},
                                                  {"output", out.string()}},
                                   2)
              << "\n";
  } else {
    std::cout << fmt::format("shuffled {} ({} frames) with seed {} -> {}\n", m.movie, shuffle.frames.size(), m.seed, out.string());
  }
  return kExitOk;
}

int cmd_movie_show(const std::string& file, bool json) {
  compiler::Diagnostics diags;
  if (compiler::looks_like_shuffle(file)) {
    auto shuffle = compiler::read_shuffle(file, diags);
    std::optional<compiler::Movie> movie;
    if (shuffle) {
      // Check the shuffle against its movie when the movie is still there.
      const fs::path movie_path = fs::path(file).parent_path() / shuffle->movie;
      auto f = std::make_shared<const compiler::SourceFile>(file, "");
      if (fs::exists(movie_path)) {
        movie = compiler::read_movie(movie_path, diags);
        if (movie) compiler::check_shuffle_against_movie(*shuffle, *movie, compiler::SourceLocation{f, 0, 0, 1}, diags);
      } else {
        diags.warning("W0520", compiler::SourceLocation{f, 0, 0, 1},
                      "the shuffled movie '" + movie_path.string() + "' is not there; the frames are not checked against it",
                      "keep the shuffle beside its movie");
      }
    }
    std::cerr << compiler::format_diagnostics(diags);
    if (!shuffle || diags.has_errors()) {
      if (json)
        std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(diags)}}, 2)
                  << "\n";
      return kExitBadInput;
    }
    if (json) {
      nlohmann::json frames = nlohmann::json::array();
      for (const auto& fr : shuffle->frames) frames.push_back({{"original_index", fr.original_index}, {"name", fr.name}});
      std::cout << schema::json_text(nlohmann::json{{"ok", true},
                                                    {"kind", "shuffle"},
                                                    {"movie", shuffle->movie},
                                                    {"date", shuffle->date},
                                                    {"time", shuffle->time},
                                                    {"frames", frames},
                                                    {"checked_against_movie", movie.has_value()}},
                                     2)
                << "\n";
      return kExitOk;
    }
    std::cout << fmt::format("{}: shuffle of movie {} made {} {}, {} frames{}\n", file, shuffle->movie, shuffle->date,
                             shuffle->time, shuffle->frames.size(), movie ? " (matches the movie)" : "");
    for (std::size_t k = 0; k < shuffle->frames.size(); ++k)
      std::cout << fmt::format("  {:>3}  {}  (frame {} of the movie)\n", k + 1, shuffle->frames[k].name,
                               shuffle->frames[k].original_index);
    return kExitOk;
  }
  auto movie = compiler::read_movie(file, diags);
  std::cerr << compiler::format_diagnostics(diags);
  if (!movie) {
    if (json)
      std::cout << schema::json_text(nlohmann::json{{"ok", false}, {"diagnostics", diagnostics_json(diags)}}, 2)
                << "\n";
    return kExitBadInput;
  }
  if (json) {
    std::cout << schema::json_text(nlohmann::json{{"ok", true}, {"kind", "movie"}, {"frames", movie->frames}}, 2)
              << "\n";
    return kExitOk;
  }
  std::cout << fmt::format("{}: movie, {} frame{} (at most {})\n", file, movie->frames.size(),
                           movie->frames.size() == 1 ? "" : "s", compiler::kMaxMovieFrames);
  for (std::size_t k = 0; k < movie->frames.size(); ++k) std::cout << fmt::format("  {:>3}  {}\n", k + 1, movie->frames[k]);
  return kExitOk;
}

}  // namespace sandpaper::cli
