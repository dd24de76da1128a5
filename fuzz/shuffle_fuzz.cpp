// Shuffle files (thesis Appendix B; compiler/movie.hpp) through parse_shuffle. An accepted shuffle
// must come back field for field through format_shuffle, and is checked against a 12-frame movie
// (the golden shuffle's). Bad input is a diagnostic; nothing is caught here.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "fuzz_support.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/movie.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sandpaper;
  auto file = std::make_shared<const compiler::SourceFile>(
      "<fuzz>.shuffle", std::string(reinterpret_cast<const char*>(data), size));
  compiler::Diagnostics diags;
  const auto shuffle = compiler::parse_shuffle(file, diags);
  (void)compiler::format_diagnostics(diags);
  fuzz::check(shuffle.has_value() == !diags.has_errors(), "parse_shuffle: a shuffle and errors, or neither");
  if (!shuffle) return 0;

  const std::string text = compiler::format_shuffle(*shuffle);
  compiler::Diagnostics again_diags;
  const auto again = compiler::parse_shuffle(std::make_shared<const compiler::SourceFile>("<again>", text), again_diags);
  fuzz::check(again.has_value(), "a shuffle written by format_shuffle does not parse:\n" +
                                     compiler::format_diagnostics(again_diags));
  fuzz::check(again->movie == shuffle->movie && again->date == shuffle->date && again->time == shuffle->time,
              "a shuffle's header reads back otherwise");
  fuzz::check(again->frames.size() == shuffle->frames.size(), "a shuffle's frame count reads back otherwise");
  for (std::size_t i = 0; i < again->frames.size(); ++i)
    fuzz::check(again->frames[i].original_index == shuffle->frames[i].original_index &&
                    again->frames[i].name == shuffle->frames[i].name,
                "a shuffle's frame " + std::to_string(i + 1) + " reads back otherwise");

  compiler::Movie movie;
  movie.path = "session.movie";
  for (int i = 1; i <= 12; ++i) movie.frames.push_back("frame-" + std::to_string(i) + ".hws");
  compiler::Diagnostics fit;
  compiler::check_shuffle_against_movie(*shuffle, movie, compiler::SourceLocation{file, 1, 1, 1}, fit);
  (void)compiler::format_diagnostics(fit);
  return 0;
}
