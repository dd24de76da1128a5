#pragma once
// Running a tool and reading what it prints (internal to sandpaper_curation): `library review`
// asks git what changed. No shell: the arguments go to the program as they are.
#include <optional>
#include <string>
#include <vector>

namespace sandpaper::curation {

// Runs argv[0] (found on PATH) with `argv`, stdin from /dev/null and stderr to `err` (when not null);
// its stdout, or nullopt if it could not be started or exited non-zero.
std::optional<std::string> run_capture(const std::vector<std::string>& argv, std::string* err = nullptr);

}  // namespace sandpaper::curation
