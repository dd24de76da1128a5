/*
 * The lab's simulated motor drivers, in the slots of the firmware's RMD CAN motor classes.
 *
 * Shadows Firmware/FFBoard/UserExtensions/Inc/RmdMotorCAN.h by include order: Axis.cpp and
 * MotorDriver.cpp (the only includers) find this one first, and their chooser lists keep
 * RmdMotorCAN1 at selection id 11 (axis X) and RmdMotorCAN2 at 12 (axis Y). Why this slot: the
 * header is included only from FFBoard/Src, where include order decides; TMC4671.h and MotorPWM.h
 * are also included from UserExtensions/Inc/FFBHIDMain.h, whose own folder is searched first.
 *
 * A simulated driver is a MotorDriver with an integrated Encoder, like the RMD motor (and a
 * TMC4671 with its own encoder): turn() hands the Axis's torque to the simulated stick, getPos()
 * reads the stick's position in encoder counts. It keeps the real driver's switching: torque is
 * taken only between startMotor() and stopMotor(), and both set it to 0. Convention, as for an
 * aligned FOC drive: positive torque accelerates the handle toward increasing encoder counts.
 */
#ifndef SANDPAPER_LAB_RMDMOTORCAN_H
#define SANDPAPER_LAB_RMDMOTORCAN_H

#include "Encoder.h"
#include "MotorDriver.h"

#ifdef RMDCAN

class RmdMotorCAN : public MotorDriver, public Encoder {
 public:
  explicit RmdMotorCAN(uint8_t axis);  // axis 0 = X, 1 = Y (the stick_link slot)
  ~RmdMotorCAN() override;

  const ClassIdentifier getInfo() override = 0;
  void turn(int16_t power) override;
  void stopMotor() override;
  void startMotor() override;
  bool motorReady() override;
  Encoder* getEncoder() override;
  bool hasIntegratedEncoder() override;

  EncoderType getEncoderType() override;
  int32_t getPos() override;
  void setPos(int32_t pos) override;
  uint32_t getCpr() override;

  static constexpr uint32_t counts_per_rotation = 0xffff;  // as the TMC4671's position register

 private:
  void setTorque(int16_t torque);
  const uint8_t axis_index;
  bool active = false;
  int32_t posOffset = 0;  // set by setPos (the firmware's "zero encoder")
};

class RmdMotorCAN1 : public RmdMotorCAN {
 public:
  RmdMotorCAN1() : RmdMotorCAN{0} { inUse = true; }
  ~RmdMotorCAN1() override { inUse = false; }
  const ClassIdentifier getInfo() override;
  static bool isCreatable();
  static ClassIdentifier info;
  static bool inUse;
};

class RmdMotorCAN2 : public RmdMotorCAN {
 public:
  RmdMotorCAN2() : RmdMotorCAN{1} { inUse = true; }
  ~RmdMotorCAN2() override { inUse = false; }
  const ClassIdentifier getInfo() override;
  static bool isCreatable();
  static ClassIdentifier info;
  static bool inUse;
};

#endif  // RMDCAN
#endif  // SANDPAPER_LAB_RMDMOTORCAN_H
