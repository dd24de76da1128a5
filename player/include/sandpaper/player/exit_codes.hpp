#pragma once
// Exit codes shared by `sandpaper` and `sandpaper-play`: 0 success, 1 the input is wrong
// (diagnostics printed), 2 usage or environment errors, 3 internal errors.
namespace sandpaper::cli {
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitInternal = 3;
}  // namespace sandpaper::cli
