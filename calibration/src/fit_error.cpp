#include "sandpaper/calibration/fit_error.hpp"

namespace sandpaper::calibration {
namespace {

std::string format(const std::string& file, int line, const std::string& message) {
  return file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": error: " + message;
}

}  // namespace

FitError::FitError(std::string file_, int line_, std::string message_)
    : std::runtime_error(format(file_, line_, message_)), file(std::move(file_)), line(line_), message(std::move(message_)) {}

}  // namespace sandpaper::calibration
