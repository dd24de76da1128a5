# Sign and direction: a spring to the patch centre played while the hand holds the handle at
# (AT_X_MM, AT_Y_MM), so the compiled force points back toward the centre on both axes with
# opposite signs. The hand circles that point by a few micrometres (CIRCLE_MM across), so that
# the firmware, which resends an unchanged position only every 101 updates, keeps reporting.
# Writes /out/run.json, /out/trace.csv and the device's logs.
. /lab/ffboard.sh
ffboard_plug --hand circle --extent "$CIRCLE_MM" --speed "$SPEED_MM_S" --at "$AT_X_MM" "$AT_Y_MM" || exit 1
"$SANDPAPER" run -e "spring $STIFFNESS" --device usb --duration "$SECONDS" $LAB_RUN_GUARDS --json --trace /out/trace.csv \
  > /out/run.json 2> /out/run.err
run_status=$?
ffboard_stop
sed 's/^/run: /' /out/run.err
echo "{\"run_status\": $run_status}" > /out/direction.json
