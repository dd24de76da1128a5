#pragma once
// Paths that outside input names (a page's request, a glTF asset's image URI) resolved inside one
// folder and nowhere else: "..", absolute paths and symbolic links that lead out are refused.
#include <filesystem>
#include <stdexcept>
#include <string>

namespace sandpaper::schema {

struct OutsideFolder : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `relative` resolved inside `root` (which must exist), symbolic links followed: the result is
// absolute and lexically inside root's canonical path. Throws OutsideFolder for an empty or absolute
// path, a NUL, a path that climbs out with "..", a link that points outside, or one that cannot be
// resolved; its message names the path and `folder` ("the studio's folder") and ends with `rule`
// when given (what the reader does instead).
std::filesystem::path confined_path(const std::filesystem::path& root, const std::string& relative,
                                    const std::string& folder, const std::string& rule = "");

}  // namespace sandpaper::schema
