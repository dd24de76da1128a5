#pragma once
// The one error the calibration fitting tools throw: data that cannot support a fit, or a file that
// cannot be read. It carries the place (file, 1-based line; 0 = the file as a whole) so the CLI can
// print `file:line: error: message` as the house diagnostics do.
#include <stdexcept>
#include <string>

namespace sandpaper::calibration {

struct FitError : std::runtime_error {
  // what() is the formatted diagnostic "file:line: error: message" ("file: error: message" when line is 0).
  FitError(std::string file, int line, std::string message);
  std::string file;
  int line = 0;
  std::string message;  // what is wrong and what is missing, without the place
};

}  // namespace sandpaper::calibration
