#pragma once
// The fuzzing build (tools/fuzz.sh) instruments every comparison for coverage feedback. In loops that
// run once per sample or per multiply-add, that is the loop bound, checked millions of times, and it
// made compiles within the stated limits take 10 to 30 times their release time, past libFuzzer's
// 25 s (the blur and the height field; docs/RELIABILITY.md), and slowed every target that compiles.
// Those comparisons carry no coverage worth having; ASan still checks every access. Only such
// numeric kernels are marked, and the branches on their results stay in instrumented callers.
// Figures per target are in docs/RELIABILITY.md ("Executions per second").
#if defined(__clang__)
#define SANDPAPER_NO_COVERAGE __attribute__((no_sanitize("coverage")))
#else
#define SANDPAPER_NO_COVERAGE
#endif
