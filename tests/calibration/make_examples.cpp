// Writes the synthetic example data of examples/calibration/ (examples.cpp says how they are made).
// Usage: make_calibration_examples <examples/calibration directory>
#include <filesystem>
#include <iostream>

#include "examples.hpp"
#include "sandpaper/schema/atomic_file.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_calibration_examples <directory>\n";
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  using namespace sandpaper::calibration::synthetic;
  sandpaper::schema::write_file_atomically(dir / "roughness-responses.csv", roughness_responses_example());
  sandpaper::schema::write_file_atomically(dir / "openffboard-readings.csv", openffboard_readings_example());
  std::cout << "wrote " << (dir / "roughness-responses.csv").string() << " and " << (dir / "openffboard-readings.csv").string() << "\n";
  return 0;
}
