// Compiled (syntax only) by code_check_test.sh with RAISE set to a code: a registered one compiles,
// an unregistered one must not.
#include "sandpaper/compiler/diagnostic.hpp"

void raise(sandpaper::compiler::Diagnostics& d) { d.error(RAISE, {}, "message"); }
