#pragma once
// Fuzz build only (fuzz/CMakeLists.txt force-includes this into runtime/src/patch_evaluator.cpp):
// clang before 17 does not deduce template arguments of aggregates (P1816), and that file's
// `Overloaded{...}` visitor has no deduction guide (compiler/src/editing/parameters.cpp's has one). The
// guide is declared here, for the file's own template, ahead of its definition: same unnamed
// namespace, same translation unit. Remove once patch_evaluator.cpp declares the guide itself.
namespace sandpaper::runtime {
namespace {
template <class... Ts>
struct Overloaded;
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;
}  // namespace
}  // namespace sandpaper::runtime
