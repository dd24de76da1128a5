#pragma once
// A material's (or a workspace's) numbers as tunable parameters, and the edit that changes one of
// them in the source text: only the number's characters change, so comments, layout and every other
// number stay as written (the studio's sliders, docs/STUDIO.md "Parameters").
#include <stdexcept>
#include <string>
#include <vector>

#include "sandpaper/calibration/calibration.hpp"

namespace sandpaper::compiler {

// One number written in the text, with where it is and the range a slider offers for it.
struct Parameter {
  std::string name;      // stable key: "roughness", "grating.period", "force.Wave.amplitude", "patch.2.x"
  std::string label;     // in words: "grating period"
  std::string layer;     // "perceptual" or "physical" (thesis 1.5.2)
  double value = 0;      // as written, in `unit`
  std::string unit;      // as written: "mm", "%", "N/m"; "" for a plain number or a percept
  double si = 0;         // value in SI (m, N, N/m, rad, fraction, ...)
  double min = 0, max = 0, step = 0;  // slider range and step, in `unit`; always contains `value`
  int line = 0, column = 0, length = 0;  // the number's characters only (1-based; bytes), not its unit
};

// Thrown by set_parameter for an unknown name, a unit of another dimension, or a non-finite value.
struct ParameterError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Every number of a material's text, in source order. Text that does not parse yields the numbers
// of the statements that did. Roughness ranges over the compile map's calibrated stimuli (Minsky
// 1995 Figure 19: percept_of the measured force range); periods 0.3-20 mm; forces 0 to `max_force_N`.
std::vector<Parameter> material_parameters(const std::string& text, const calibration::CalibrationSet& calibration,
                                           double max_force_N);
// Every number of a workspace's text: "workspace.width", "patch.<i>.x", "patch.<i>.width", ... (i from 0).
std::vector<Parameter> workspace_parameters(const std::string& text);

// `text` with parameter `name` (one of `params`, listed from this same text) set to `value` in `unit`
// ("" = the unit written). The number is converted to the written unit and only its characters are
// replaced. Throws ParameterError.
std::string set_parameter(const std::string& text, const std::vector<Parameter>& params, const std::string& name,
                          double value, const std::string& unit = "");

// Places workspace patch `index` (0-based) at centre (x, y) with size w x h, all mm: rewrites its
// numbers, inserting `size W mm x H mm` (or `x H mm`) where the file left the size to the material.
// Throws ParameterError for an index out of range or a non-finite or non-positive size.
std::string place_workspace_patch(const std::string& text, int index, double x_mm, double y_mm, double width_mm,
                                  double height_mm);

// The shortest decimal text (at most 6 significant digits) for a slider's value: "3", "2.55", "0.0125".
std::string format_parameter_value(double value);

}  // namespace sandpaper::compiler
