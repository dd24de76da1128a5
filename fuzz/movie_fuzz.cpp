// Movie files (thesis Appendix B; compiler/movie.hpp) through read_movie, which takes a path: the
// input is one scratch file beside the workspaces the corpus names (sampler.hws, ..., frame-1.hws
// ... frame-12.hws, empty files: the reader checks only that they exist). An accepted movie must
// come back unchanged through format_movie, and a shuffle of it must be well formed, read back, and
// fit the movie. Bad input is a diagnostic; nothing is caught here.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "fuzz_support.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/movie.hpp"

namespace {
const std::filesystem::path& movie_dir() {
  static const std::filesystem::path dir = [] {
    auto d = sandpaper::fuzz::scratch_dir() / "movie";
    std::filesystem::create_directories(d);
    for (const char* name : {"sampler.hws", "periods.hws", "cloths.hws", "three-layers.hws", "a.hws"})
      sandpaper::fuzz::write_file(d / name, "");
    for (int i = 1; i <= 12; ++i) sandpaper::fuzz::write_file(d / ("frame-" + std::to_string(i) + ".hws"), "");
    return d;
  }();
  return dir;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  const auto path = movie_dir() / "input.movie";
  fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
  compiler::Diagnostics diags;
  const auto movie = compiler::read_movie(path, diags);
  (void)compiler::format_diagnostics(diags);
  fuzz::check(movie.has_value() == !diags.has_errors(), "read_movie: a movie and errors, or neither");
  if (!movie) return 0;
  fuzz::check(!movie->frames.empty() && movie->frames.size() <= compiler::kMaxMovieFrames, "accepted frame count");

  // What the reader accepts, the writer writes (it throws std::invalid_argument otherwise: a finding).
  const auto again_path = movie_dir() / "again.movie";
  fuzz::write_file(again_path, compiler::format_movie(movie->frames));
  compiler::Diagnostics again_diags;
  const auto again = compiler::read_movie(again_path, again_diags);
  fuzz::check(again && again->frames == movie->frames, "a movie written by format_movie reads back otherwise");

  const auto shuffle = compiler::shuffle_movie(*movie, size, "input.movie", "1995-06-01", "14:30:00");
  const auto text = compiler::format_shuffle(shuffle);
  compiler::Diagnostics shuffle_diags;
  const auto read = compiler::parse_shuffle(std::make_shared<const compiler::SourceFile>("<shuffle>", text), shuffle_diags);
  fuzz::check(read.has_value(), "a shuffle written by format_shuffle does not parse:\n" +
                                     compiler::format_diagnostics(shuffle_diags));
  compiler::check_shuffle_against_movie(*read, *movie, compiler::SourceLocation{}, shuffle_diags);
  fuzz::check(!shuffle_diags.has_errors(), "a movie's own shuffle does not fit it:\n" +
                                                compiler::format_diagnostics(shuffle_diags));
  return 0;
}
