#pragma once
// Writing TOML by hand for the calibration writers: the files are read by people too, so keys come
// in the order docs/CALIBRATION.md shows them, with comments, which a TOML serializer cannot do.
#include <string>
#include <string_view>

namespace sandpaper::calibration::detail {

// A basic TOML string: quoted, with \ " and control characters escaped.
std::string toml_string(std::string_view s);
// A TOML float with `digits` significant digits that is always a float ("1.0", not "1").
std::string toml_float(double v, int digits = 6);

}  // namespace sandpaper::calibration::detail
