#pragma once
// Movie and shuffle files (thesis Appendix B, "File Formats"). A movie is a list of workspace file
// names, one a line, relative to the movie file's folder, at most 100 frames. A shuffle records one
// shuffled presentation order of a movie, for experiments:
//     Movie: <movie file>
//     Date: <date>
//     Time: <time>
//     <blank line>
//     <original index> <name>        one line per frame, in the shuffled order
// Codes E0510-E0513 (movies) and E0520-E0525 (shuffles): schema/LANGUAGE.md, "Movies and shuffles".
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"

namespace sandpaper::compiler {

// Thesis Appendix B, "Implementation Limits": maximum number of frames per movie.
inline constexpr std::size_t kMaxMovieFrames = 100;

struct Movie {
  std::filesystem::path path;                 // the movie file, as given
  std::vector<std::string> frames;            // workspace file names as written, relative to its folder
  std::vector<SourceLocation> frame_locations;  // where each name is (empty for movies built in code)
};

// Reads a movie: names separated by CR, LF or CRLF (the Macintosh wrote CR); surrounding
// whitespace and blank lines are ignored. Errors: E0510 cannot open, E0511 more than 100 frames,
// E0512 a frame's file does not exist, E0513 no frames. Returns nullopt after any error.
std::optional<Movie> read_movie(const std::filesystem::path& path, Diagnostics& diags);

// The file text of a movie: one name a line. Throws std::invalid_argument beyond 100 frames or for
// an empty name or one with a line break.
std::string format_movie(const std::vector<std::string>& frames);
// format_movie written atomically to `path`.
void write_movie(const std::filesystem::path& path, const std::vector<std::string>& frames);

struct ShuffleEntry {
  std::size_t original_index = 0;  // 1-based position in the unshuffled movie
  std::string name;
};

struct Shuffle {
  std::string movie;  // the movie file, relative to the shuffle file's folder
  std::string date;   // YYYY-MM-DD
  std::string time;   // HH:MM:SS, 24-hour, local
  std::vector<ShuffleEntry> frames;  // shuffled order
};

// Shuffles `movie` with seeded_permutation(frames, seed): the same seed gives the same order on
// every platform. `movie_name` goes into the "Movie:" line.
Shuffle shuffle_movie(const Movie& movie, std::uint64_t seed, std::string movie_name, std::string date,
                      std::string time);

std::string format_shuffle(const Shuffle& shuffle);
// Parses shuffle text; lines may end in CR, LF or CRLF. Errors: E0521 header, E0522 frame line,
// E0523 original indices not 1..N each once. Returns nullopt after any error.
std::optional<Shuffle> parse_shuffle(const std::shared_ptr<const SourceFile>& file, Diagnostics& diags);
// E0520 if it cannot be opened, then parse_shuffle.
std::optional<Shuffle> read_shuffle(const std::filesystem::path& path, Diagnostics& diags);
// Whether the file starts like a shuffle ("Movie:").
bool looks_like_shuffle(const std::filesystem::path& path);

// E0524 where the shuffle does not fit the movie: another number of frames, or a name that is not
// the movie's name at its original index. `where` locates the shuffle in diagnostics.
void check_shuffle_against_movie(const Shuffle& shuffle, const Movie& movie, const SourceLocation& where,
                                 Diagnostics& diags);

// Sandpaper computed a shuffle's file name from the movie's name and the date and time; ours is
// "<movie stem>-<YYYYMMDD>-<HHMMSS>.shuffle" beside the movie.
std::filesystem::path default_shuffle_path(const std::filesystem::path& movie, const std::string& date,
                                           const std::string& time);
// YYYY-MM-DD with a real month and day; HH:MM:SS within 00:00:00-23:59:60.
bool is_valid_date(const std::string& date);
bool is_valid_time(const std::string& time);
// The system clock's local date and time in those forms.
void local_date_time_now(std::string& date, std::string& time);

}  // namespace sandpaper::compiler
