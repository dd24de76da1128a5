# Plays MATERIAL on the emulated OpenFFBoard for SECONDS through one of the kernel's paths, the
# kernel's driver left bound: THROUGH=hidraw (`sandpaper run --device hidraw:NODE`, the HID PID driver
# on the hidraw node) or THROUGH=evdev (`--device evdev:NODE`, the kernel's hid-pidff through the input
# event node). As a user without root (uid 1000, given the node as udev's uaccess tag would give it to
# the person at the seat), the stick moved by the lab's scripted hand (HAND, SPEED_MM_S, EXTENT_MM).
# Writes /out/run.json, /out/trace.csv, the device's logs (reports.csv, torque.csv, state.json) and
# /out/path.json (the kernel's driver and input device before, during and after the run, and how
# many output reports usbhid dropped with "output queue full").
# UNCALIBRATED=1 (evdev only): the user's calibration folder is a copy of CALIBRATION_SRC without
# the OpenFFBoard's file, so the joystick is a device no calibration file names: a run without
# --uncalibrated must be refused (/out/refused.err), and the run plays with --uncalibrated.
. /lab/ffboard.sh
# MAIN_CLASS=wheel: the firmware's 1-axis wheel, its encoder's half range HALF_RANGE_MM of rim;
# MODEL=sidewinder-ff2: the HID PID model with the FF2's descriptor (ffboard.sh).
ffboard_plug --hand "$HAND" --speed "$SPEED_MM_S" --extent "$EXTENT_MM" --half-range "${HALF_RANGE_MM:-50}" || exit 1
THROUGH=${THROUGH:-hidraw}
driver_before=$(ffboard_interface_driver)
lab_wait_input "$FFB_USB_DEV" 10
input_before=$LAB_INPUT
case $THROUGH in
  hidraw) node=/dev/$LAB_HIDRAW ;;
  evdev) node=/dev/input/${LAB_INPUT#input/} ;;
  *) echo "lab: THROUGH=$THROUGH: hidraw or evdev" >&2; exit 2 ;;
esac
queue_full_before=$(dmesg | grep -c "output queue full")
# hid-pidff, which binds a device whose descriptor has every report it needs, says so at info level.
pidff=$(dmesg | grep -c "Force feedback for USB HID PID devices")

grep -q '^player:' /etc/passwd 2>/dev/null || echo 'player:x:1000:1000:player:/tmp/player:/bin/sh' >> /etc/passwd
grep -q '^player:' /etc/group 2>/dev/null || echo 'player:x:1000:' >> /etc/group
mkdir -p /tmp/player && chown 1000:1000 /tmp/player
chown 1000 "$node"
as_player=""
uncalibrated=""
refused_status=null
if [ "${UNCALIBRATED:-0}" = 1 ]; then
  # (the FF2 has no file to take away)
  cp -r "$CALIBRATION_SRC" /tmp/player/calibration && rm -f /tmp/player/calibration/devices/openffboard-2axis.toml || exit 1
  chown -R 1000:1000 /tmp/player/calibration
  as_player="SANDPAPER_CALIBRATION=/tmp/player/calibration "
  uncalibrated="--uncalibrated"
  su player -s /bin/sh -c "${as_player}exec \"$SANDPAPER\" run \"$MATERIAL\" --device $THROUGH:$node --duration 0.3 $LAB_RUN_GUARDS" \
    > /dev/null 2> /out/refused.err
  refused_status=$?
  sed 's/^/refused: /' /out/refused.err
fi
lab_step "playing through $node as $(su player -s /bin/sh -c id)"
su player -s /bin/sh -c "${as_player}exec \"$SANDPAPER\" devices" > /out/devices.txt 2>&1
devices_status=$?
sed 's/^/devices: /' /out/devices.txt

su player -s /bin/sh -c "${as_player}exec \"$SANDPAPER\" run \"$MATERIAL\" --device $THROUGH:$node $uncalibrated --duration $SECONDS $LAB_RUN_GUARDS \
  --json --trace /tmp/player/trace.csv" > /out/run.json 2> /out/run.err &
run_pid=$!
# Ready once the run holds the node open (its open sequence has begun); the driver bound then is the
# one a user's other programs see while Sandpaper plays.
_run_holds_node() {
  local fd
  for fd in /proc/[0-9]*/fd/*; do
    [ "$(readlink "$fd" 2>/dev/null)" = "$node" ] && return 0
  done
  return 1
}
lab_poll 30 "the run to open $node" _run_holds_node
driver_during=$(ffboard_interface_driver)
lab_wait_input "$FFB_USB_DEV" 1
input_during=$LAB_INPUT
wait "$run_pid"
run_status=$?
cp /tmp/player/trace.csv /out/trace.csv 2>/dev/null
# Without --device, run takes a calibrated joystick this user may open, through hidraw before evdev
# (only the node of THROUGH was given to the user, so each scenario sees the other path closed).
su player -s /bin/sh -c "${as_player}exec \"$SANDPAPER\" run -e 'spring 100 N/m' --duration 0.3 $LAB_RUN_GUARDS --json" \
  > /out/default.json 2> /out/default.err
default_status=$?
sed 's/^/default: /' /out/default.err
driver_after=$(ffboard_interface_driver)
ffboard_stop
sed 's/^/run: /' /out/run.err
queue_full=$(( $(dmesg | grep -c "output queue full") - queue_full_before ))
cat > /out/path.json <<JSON
{"through": "$THROUGH", "run_status": $run_status, "refused_status": $refused_status, "node": "$node", "output_queue_full": $queue_full, "default_status": $default_status, "driver_before": "$driver_before", "driver_during": "$driver_during",
 "driver_after": "$driver_after", "input_before": "$input_before", "input_during": "$input_during", "pidff_bound": $pidff,
 "devices_status": $devices_status}
JSON
dmesg > /out/dmesg.log
cat /out/path.json
