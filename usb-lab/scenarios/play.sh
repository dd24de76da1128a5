# Plays MATERIAL on the emulated OpenFFBoard for SECONDS with `sandpaper run --device usb`, the
# stick moved by the lab's scripted hand (HAND, SPEED_MM_S, EXTENT_MM). Writes /out/run.json (the
# run's summary), /out/trace.csv (every tick), the device's logs (reports.csv, torque.csv,
# state.json) and /out/play.json (the kernel driver before, during and after).
# MAIN_CLASS=wheel: the firmware's 1-axis wheel, its encoder's half range HALF_RANGE_MM of rim.
. /lab/ffboard.sh
ffboard_plug --hand "$HAND" --speed "$SPEED_MM_S" --extent "$EXTENT_MM" --half-range "${HALF_RANGE_MM:-50}" || exit 1
driver_before=$(ffboard_interface_driver)

"$SANDPAPER" run "$MATERIAL" --device usb --duration "$SECONDS" $LAB_RUN_GUARDS --json --trace /out/trace.csv \
  > /out/run.json 2> /out/run.err &
run_pid=$!
ffboard_wait_claimed "the run"
wait "$run_pid"
run_status=$?
ffboard_given_back
ffboard_stop
sed 's/^/run: /' /out/run.err
cat > /out/play.json <<JSON
{"run_status": $run_status, "driver_before": "$driver_before", "driver_during": "$DRIVER_DURING",
 "driver_after": "$DRIVER_AFTER", "input_after": "$INPUT_AFTER"}
JSON
cat /out/play.json
