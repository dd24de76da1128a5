// The lab's simulated motor drivers (RmdMotorCAN.h says why they sit in the RMD slots).
#include "RmdMotorCAN.h"

#include "stick_link.hpp"

namespace stick = sandpaper::usb_lab::stick_link;

// Names the firmware lists for drivers 11 and 12 (axis.drvtype info); ids as the RMD classes'.
ClassIdentifier RmdMotorCAN1::info = {.name = "Lab simulated stick motor (X)", .id = CLSID_MOT_RMD1};
ClassIdentifier RmdMotorCAN2::info = {.name = "Lab simulated stick motor (Y)", .id = CLSID_MOT_RMD2};
bool RmdMotorCAN1::inUse = false;
bool RmdMotorCAN2::inUse = false;

const ClassIdentifier RmdMotorCAN1::getInfo() { return info; }
const ClassIdentifier RmdMotorCAN2::getInfo() { return info; }
bool RmdMotorCAN1::isCreatable() { return !inUse; }
bool RmdMotorCAN2::isCreatable() { return !inUse; }

RmdMotorCAN::RmdMotorCAN(uint8_t axis) : axis_index(axis) {
  cpr = counts_per_rotation;
  stick::axis(axis_index).driver_exists = true;
}

RmdMotorCAN::~RmdMotorCAN() {
  stick::axis(axis_index).driver_enabled = false;
  stick::axis(axis_index).driver_exists = false;
}

void RmdMotorCAN::setTorque(int16_t torque) { stick::publish_torque(axis_index, torque); }

void RmdMotorCAN::turn(int16_t power) {
  if (!active) return;  // a stopped drive ignores torque, as the RMD and TMC4671 drivers do
  setTorque(power);
}

void RmdMotorCAN::stopMotor() {
  active = false;
  stick::axis(axis_index).driver_enabled = false;
  setTorque(0);
}

void RmdMotorCAN::startMotor() {
  active = true;
  stick::axis(axis_index).driver_enabled = true;
  setTorque(0);
}

bool RmdMotorCAN::motorReady() { return true; }  // always present, never in fault
Encoder* RmdMotorCAN::getEncoder() { return static_cast<Encoder*>(this); }
bool RmdMotorCAN::hasIntegratedEncoder() { return true; }
EncoderType RmdMotorCAN::getEncoderType() { return EncoderType::absolute; }
uint32_t RmdMotorCAN::getCpr() { return counts_per_rotation; }
int32_t RmdMotorCAN::getPos() {
  return stick::axis(axis_index).encoder_counts.load() - posOffset;
}
void RmdMotorCAN::setPos(int32_t pos) { posOffset = stick::axis(axis_index).encoder_counts.load() - pos; }
