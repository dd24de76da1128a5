#pragma once
// The shipped example data of examples/calibration/, as the generator makes them. The
// examples test checks that the files in the tree are exactly these texts.
#include <string>

namespace sandpaper::calibration::synthetic {

std::string roughness_responses_example();   // examples/calibration/roughness-responses.csv
std::string openffboard_readings_example();  // examples/calibration/openffboard-readings.csv

}  // namespace sandpaper::calibration::synthetic
