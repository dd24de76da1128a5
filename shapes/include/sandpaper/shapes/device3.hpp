#pragma once
// What a 3-D servo run needs of a 3-DOF force-feedback device (a Novint Falcon, a Haply Inverse3,
// the simulated sim3d): runtime::Device (runtime/device.hpp) with positions and forces in 3-D.
// Positions are in metres in the scene's frame (x right, y up, z toward the user, as glTF and
// SceneProgram), forces in newtons. Functions ending _rt run on the servo thread and must not
// allocate, lock, log or do I/O. docs/SHAPES.md, "The 3-DOF device model".
#include <string>

#include <glm/vec3.hpp>

#include "sandpaper/calibration/calibration.hpp"

namespace sandpaper::shapes {

// The volume a 3-DOF handle reaches, centred on the scene's origin: a box (width x height x depth
// along x, y, z) or a sphere (its diameter on every axis), m.
struct Workspace3 {
  bool sphere = true;
  glm::dvec3 size_m{0.2286};  // box: the three sides; sphere: the diameter three times
  // Whether p (m, scene frame) lies inside or on the boundary.
  bool contains(const glm::dvec3& p_m) const noexcept;
};

// A 3-DOF device's limits as data, SI units (runtime::DeviceLimits in 3-D).
struct DeviceLimits3 {
  std::string name;              // "sim3d"
  double max_force_N = 10.0;     // the force vector's magnitude never exceeds this
  double min_rate_hz = 900.0;    // servo rates the device supports
  double max_rate_hz = 10000.0;
  Workspace3 workspace;
};

// The limits a three-axis device file states (calibration/devices/, axes 3: [force.z] and a box or
// sphere [workspace]). Throws std::invalid_argument for a device with one or two axes, naming it.
DeviceLimits3 limits3_of(const calibration::DeviceCalibration& device);

// sim3d's limits as calibration/devices/sim3d.toml states them (compiled in at build time, as
// runtime::sim_device_limits() compiles in sim.toml): 10 N, 900 Hz - 10 kHz, a 9-inch sphere.
// Throws calibration::CalibrationError only if the embedded file were invalid.
const DeviceLimits3& sim3d_limits();
// The embedded sim3d.toml, parsed (for a caller that needs the calibration itself, e.g. to compile
// materials for sim3d without a calibration folder).
const calibration::DeviceCalibration& sim3d_calibration();

// A 3-DOF device as the 3-D servo run plays it (scene_servo.hpp).
class Device3 {
 public:
  virtual ~Device3() = default;
  virtual const DeviceLimits3& limits() const noexcept = 0;
  // Whether the device can follow simulated time (a simulated one can; one a person holds cannot).
  virtual bool follows_virtual_clock() const noexcept { return true; }
  // Position of the handle (m, scene frame) at servo time t_s (s since the run started). Returns
  // false if the device could not be read.
  virtual bool read_position_rt(double t_s, glm::dvec3& position_m) noexcept = 0;
  // Commands the force (N, scene frame) until the next write. Returns false on a device fault.
  virtual bool write_force_rt(const glm::dvec3& force_N) noexcept = 0;
};

}  // namespace sandpaper::shapes
