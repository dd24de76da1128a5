#pragma once
// The fuzzing build (tools/fuzz.sh) instruments every comparison for coverage feedback. In loops that
// run once per sample or per multiply-add, that is the loop bound, checked millions of times, and it
// made compiles within the stated limits take 10 to 30 times their release time, past libFuzzer's
// 25 s (fuzz findings F11, the blur; F36, the height field). Those comparisons carry no coverage
// worth having; ASan still checks every access. Only such numeric kernels are marked. Marking the
// channel sum, the height range and the force table's read too (with fuzz::read_file in the
// harnesses and the workspace reader's copies gone) cut the workspace target's CPU time an input by
// 31 % (500 of its corpus inputs, 12.6 s to 8.7 s user + sys, 2026-11-24).
#if defined(__clang__)
#define SANDPAPER_NO_COVERAGE __attribute__((no_sanitize("coverage")))
#else
#define SANDPAPER_NO_COVERAGE
#endif
