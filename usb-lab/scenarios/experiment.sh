# Lab test 6, an experiment: `sandpaper experiment run DESIGN --device usb` with the simulated
# observer OBSERVER on the emulated OpenFFBoard, the stick scanned by the lab's hand (SPEED_MM_S
# over EXTENT_MM), results in /out/results. Writes /out/experiment.out and .err (what it printed),
# the device's logs and /out/experiment.json (exit status, the kernel driver before, during and
# after).
. /lab/ffboard.sh
ffboard_plug --hand scan --speed "$SPEED_MM_S" --extent "$EXTENT_MM" || exit 1
driver_before=$(ffboard_interface_driver)
rm -rf /out/results  # a kept --out folder from an earlier run: the experiment refuses to mix sessions
# shellcheck disable=SC2086
"$SANDPAPER" experiment run "$DESIGN" --subject LAB --observer "$OBSERVER" --device usb $LAB_RUN_GUARDS -o /out/results \
  > /out/experiment.out 2> /out/experiment.err &
experiment_pid=$!
ffboard_wait_claimed "the experiment"
wait "$experiment_pid"
experiment_status=$?
ffboard_given_back
ffboard_stop
sed 's/^/experiment: /' /out/experiment.err
cat > /out/experiment.json <<JSON
{"experiment_status": $experiment_status, "driver_before": "$driver_before", "driver_during": "$DRIVER_DURING",
 "driver_after": "$DRIVER_AFTER", "input_after": "$INPUT_AFTER"}
JSON
cat /out/experiment.json
