#pragma once
// Copies of tests/curation/data/mini/ (and of the shipped calibration) in temp folders, to break one
// thing at a time.
#include <filesystem>
#include <string>

#include "sandpaper/compiler/diagnostic.hpp"

namespace sandpaper::test {

// A fresh copy of the mini library; returns its folder.
std::filesystem::path mini_library_copy(const std::string& tag);
// A fresh copy of the shipped calibration folder.
std::filesystem::path calibration_copy(const std::string& tag);
// Replaces the first `from` in `file` with `to`; fails the test if `from` is not there.
void edit(const std::filesystem::path& file, const std::string& from, const std::string& to);
void write(const std::filesystem::path& file, const std::string& text);
std::string read(const std::filesystem::path& file);
// The diagnostics of `code` (in order).
std::vector<const compiler::Diagnostic*> with_code(const compiler::Diagnostics& d, const std::string& code);

}  // namespace sandpaper::test
