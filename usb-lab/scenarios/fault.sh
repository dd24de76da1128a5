# Plays MATERIAL on the emulated OpenFFBoard with `sandpaper run --device RUN_DEVICE` (usb, the
# default, or hidraw or evdev: usbhid stays bound) (scripted hand: HAND
# at AT_X_MM AT_Y_MM, SPEED_MM_S, EXTENT_MM) and injects FAULT once the run streams its forces (the
# device's "streaming" line):
#   unplug  the gadget leaves the bus (UDC unbound), then is plugged in again: `devices` must find
#           it and a second run (REPLAY_SECONDS) must play
#   reset   the device drops off the bus and comes straight back, as a firmware that reboots does
#   stale   the device stops sending input reports (the lab device's SIGUSR2)
#   sigint  Ctrl-C to the run
#   stall   no play: the device refuses (STALLs) Feature report STALL_REPORT_ID from the start, so
#           the run's open sequence fails
#   late    the device answers each GET_REPORT of Feature report STALL_REPORT_ID LATE_MS late, as
#           a busy device or a starved guest does; within the driver's control timeout the run
#           must open and play to its end
# Writes /out/run.json, /out/run.err, the device's logs and /out/fault.json: the run's exit status,
# the guest-clock time from the fault to the run's exit (centiseconds), and the kernel driver on
# the joystick's interface before, during and after. MAIN_CLASS=wheel: the firmware's 1-axis wheel,
# its encoder's half range HALF_RANGE_MM of rim.
. /lab/ffboard.sh
stall=
[ "$FAULT" = stall ] && stall="--stall-feature $STALL_REPORT_ID"
[ "$FAULT" = late ] && stall="--late-feature $STALL_REPORT_ID --late-ms $LATE_MS"
# shellcheck disable=SC2086
ffboard_plug --hand "$HAND" --at "$AT_X_MM" "$AT_Y_MM" --speed "$SPEED_MM_S" --extent "$EXTENT_MM" $stall \
  --half-range "${HALF_RANGE_MM:-50}" || exit 1
driver_before=$(ffboard_interface_driver)

RUN_DEVICE=${RUN_DEVICE:-usb}
"$SANDPAPER" run "$MATERIAL" --device "$RUN_DEVICE" --duration "$SECONDS" $LAB_RUN_GUARDS --json \
  > /out/run.json 2> /out/run.err &
run_pid=$!
driver_during=
fault_at=
problem=
if [ "$FAULT" = late ]; then
  ffboard_wait_claimed "the run" && driver_during=$DRIVER_DURING
elif [ "$FAULT" != stall ]; then
  if lab_wait_line "$FFB_DEVICE_LOG" "streaming" 60; then
    driver_during=$(ffboard_interface_driver)
    lab_now
    fault_at=$LAB_NOW
    # A device thread asleep in FunctionFS's ep0 read holds the function's mutex, which the unbind
    # below must take: the kernel stacks say whether one is (functionfs_device.cpp, ep0_loop).
    # They also show that the stacks were read at all: the ep0 thread waits in poll(), and a few
    # looks catch it there even if one came while it was between two polls.
    for _ in 1 2 3 4 5; do
      ep0_read_waiters=$(grep -l ffs_ep0_read /proc/"$FFB_DEVICE_PID"/task/*/stack 2>/dev/null | wc -l)
      poll_waiters=$(grep -l do_sys_poll /proc/"$FFB_DEVICE_PID"/task/*/stack 2>/dev/null | wc -l)
      [ "$poll_waiters" -ge 1 ] && break
    done
    lab_step "fault: $FAULT"
    case $FAULT in
      unplug) gadget_unbind ffboard ;;
      reset) gadget_unbind ffboard && gadget_bind ffboard "$FFB_UDC" ;;
      stale) kill -USR2 "$FFB_DEVICE_PID" ;;
      sigint) kill -INT "$run_pid" ;;
    esac
  else
    problem="the firmware never started playing within 60 s, so no $FAULT was made"
    echo "lab: $problem" >&2
  fi
fi
wait "$run_pid"
run_status=$?
lab_step "the run exited with status $run_status"
exit_after_cs=
[ -n "$fault_at" ] && exit_after_cs=$((LAB_NOW - fault_at))

# Plugged in again after an unplug; after a reset the device is already back.
replug_devices_status=
replay_status=
if [ "$FAULT" = unplug ]; then
  lab_wait_usb_gone "$FFB_VID" "$FFB_PID" 10
  lab_step "plugging in again"
  gadget_bind ffboard "$FFB_UDC" && lab_wait_usb_device "$FFB_VID" "$FFB_PID" 60 && FFB_USB_DEV=$LAB_USB_DEV &&
    lab_wait_hidraw "$FFB_USB_DEV" 60 && lab_wait_input "$FFB_USB_DEV" 60
  lab_step "plugged in; devices"
  "$SANDPAPER" devices > /out/devices.txt 2>&1
  replug_devices_status=$?
  lab_step "devices exited with status $replug_devices_status; a second run"
  sed 's/^/devices: /' /out/devices.txt
  "$SANDPAPER" run "$MATERIAL" --device "$RUN_DEVICE" --duration "$REPLAY_SECONDS" $LAB_RUN_GUARDS --json \
    > /out/replay.json 2> /out/replay.err
  replay_status=$?
  lab_step "the second run exited with status $replay_status"
  sed 's/^/replay: /' /out/replay.err
elif [ "$FAULT" = reset ]; then
  lab_wait_usb_device "$FFB_VID" "$FFB_PID" 60 && FFB_USB_DEV=$LAB_USB_DEV && lab_wait_hidraw "$FFB_USB_DEV" 60
fi
ffboard_given_back
lab_step "stopping the device"
ffboard_stop
sed 's/^/run: /' /out/run.err
cat > /out/fault.json <<JSON
{"fault": "$FAULT", "device": "$RUN_DEVICE", "run_status": $run_status, "exit_after_cs": ${exit_after_cs:-null},
 "driver_before": "$driver_before", "driver_during": "$driver_during", "driver_after": "$DRIVER_AFTER",
 "input_after": "$INPUT_AFTER", "replug_devices_status": ${replug_devices_status:-null},
 "ep0_read_waiters": ${ep0_read_waiters:-null}, "poll_waiters": ${poll_waiters:-null},
 "replay_status": ${replay_status:-null}, "problem": "${problem:-}"}
JSON
cat /out/fault.json
