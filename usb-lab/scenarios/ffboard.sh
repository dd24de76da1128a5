# shellcheck shell=dash
# Sourced by the lab's scenarios in the guest: the emulated OpenFFBoard (sandpaper-lab-device on a
# FunctionFS gadget on dummy_udc.0), plugged in, stopped and unplugged as a scenario needs it.
# /lab/params.sh (written by usb-lab/scenario.py) sets SANDPAPER, SANDPAPER_PLAY, LAB_DEVICE, REPO
# and the scenario's own parameters.
. /lab/params.sh
. "$LAB_GADGET"

FFB_UDC=dummy_udc.0
FFB_DEVICE_LOG=/tmp/ffboard-device.log
# What the scenarios give `run --device usb` so that the fault or figure under test, not the TCG
# guest's punctuality, ends a run: a loaded machine stalls the guest for hundreds of milliseconds,
# past the servo's 50 ms deadline guard and the driver's 202 ms watchdog for this device.
# `run`, `studio` and `experiment run` take them alike (player/include/sandpaper/player/safety_guards.hpp).
LAB_RUN_GUARDS="--deadline-guard 600000 --watchdog 1000"

# The device the lab serves: MODEL=sidewinder-ff2, the lab's HID PID model behind the SideWinder
# Force Feedback 2's recorded descriptor (usb-lab/hid_pid); else the OpenFFBoard firmware's main
# class MAIN_CLASS (joystick, or wheel: the 1-axis FFBWheel).
if [ "${MODEL:-openffboard}" = sidewinder-ff2 ]; then
  FFB_MODEL_ARGS="--model sidewinder-ff2"
else
  FFB_MODEL_ARGS="--main-class ${MAIN_CLASS:-joystick}"
fi

# The gadget as the firmware describes itself (sandpaper-lab-device --identity: key=value lines).
ffboard_create() {
  local k v vid pid bcd class subclass protocol manufacturer product serial
  while IFS='=' read -r k v; do
    case $k in
      vendor_id) vid=$v ;; product_id) pid=$v ;; bcd_device) bcd=$v ;;
      device_class) class=$v ;; device_subclass) subclass=$v ;; device_protocol) protocol=$v ;;
      manufacturer) manufacturer=$v ;; product) product=$v ;; serial_number) serial=$v ;;
    esac
  done <<IDENTITY
$("$LAB_DEVICE" --identity $FFB_MODEL_ARGS)
IDENTITY
  FFB_VID=$vid FFB_PID=$pid
  # configfs takes bcdDevice only as binary-coded decimal; the FF2's recorded 0x0A00 is not (no
  # driver Linux has matches on it).
  case $bcd in
    0x*[a-fA-F]*) echo "lab: bcdDevice $bcd is not BCD, which configfs requires: the gadget says 0x0100" >&2; bcd=0x0100 ;;
  esac
  # configfs takes no empty string; a device without a serial number (the FF2) gets the gadget's name.
  gadget_create ffboard "$vid" "$pid" bcd="$bcd" class="$class" subclass="$subclass" protocol="$protocol" \
    manufacturer="$manufacturer" product="$product" serial="${serial:-ffboard}" speed=full-speed &&
  gadget_add_ffs ffboard ffb
}

# Starts the device program with the given options; returns once it wrote its descriptors.
ffboard_start() {
  # shellcheck disable=SC2086
  "$LAB_DEVICE" --ffs /dev/ffs-ffb --log "$LAB_OUT" $FFB_MODEL_ARGS "$@" > "$FFB_DEVICE_LOG" 2>&1 &
  FFB_DEVICE_PID=$!
  lab_wait_line "$FFB_DEVICE_LOG" "ready on" 60 || { cat "$FFB_DEVICE_LOG"; return 1; }
}

# Plugs it in and waits until the host side enumerated it and usbhid bound it (hidraw).
ffboard_bind() {
  gadget_bind ffboard "$FFB_UDC" &&
  lab_wait_usb_device "$FFB_VID" "$FFB_PID" 60 &&
  FFB_USB_DEV=$LAB_USB_DEV &&
  lab_wait_hidraw "$FFB_USB_DEV" 60
}

# All three: the device as a user finds it, plugged in and bound by the kernel's HID driver.
ffboard_plug() {
  ffboard_create && ffboard_start "$@" && ffboard_bind
}

# Ends the device program (SIGTERM: it writes its logs and the firmware's state) and prints its log.
ffboard_stop() {
  [ -n "$FFB_DEVICE_PID" ] || return 0
  kill -TERM "$FFB_DEVICE_PID" 2>/dev/null
  wait "$FFB_DEVICE_PID"
  FFB_DEVICE_PID=
  sed 's/^/device: /' "$FFB_DEVICE_LOG"
}

# The driver bound to the OpenFFBoard's HID interface: usbhid, or empty when a program detached it.
ffboard_interface_driver() {
  local intf link
  for intf in "$FFB_USB_DEV"/*:1.*; do
    [ "$(cat "$intf/bInterfaceClass" 2>/dev/null)" = 03 ] || continue
    link=$(readlink "$intf/driver" 2>/dev/null) && basename "$link"
    return 0
  done
}

# While a program that claims the joystick (`run`, `experiment run`) starts: waits until usbhid let
# go of it, and sets DRIVER_DURING to the interface's driver then (usbfs: claimed through libusb).
_ffboard_detached() {
  local d
  d=$(ffboard_interface_driver)
  [ -n "$d" ] && [ "$d" != usbhid ] && DRIVER_DURING=$d
}
ffboard_wait_claimed() {
  DRIVER_DURING=
  lab_poll 30 "$1 to detach usbhid" _ffboard_detached
}

# After a run: waits until usbhid has the joystick's interface again, then sets DRIVER_AFTER (the
# interface's driver) and INPUT_AFTER (the kernel's input device for it, empty if none).
_ffboard_usbhid_back() { [ "$(ffboard_interface_driver)" = usbhid ]; }
ffboard_given_back() {
  lab_poll 10 "usbhid to be bound again" _ffboard_usbhid_back
  DRIVER_AFTER=$(ffboard_interface_driver)
  INPUT_AFTER=
  lab_wait_input "$FFB_USB_DEV" 10 && INPUT_AFTER=$LAB_INPUT
}
