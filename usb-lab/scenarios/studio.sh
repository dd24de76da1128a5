# Lab test 6, the studio: `sandpaper studio --device usb` plays a spring of STIFFNESS while the hand
# holds the handle at (AT_X_MM, AT_Y_MM), circling it by CIRCLE_MM so that the firmware keeps
# reporting. Once the firmware streams forces, the slider moves a page makes are sent, one for each
# stiffness in STIFFNESS_MOVES (N/m), each spring playing PLAY_AFTER_S (POST /api/parameter:
# spring.stiffness, by sandpaper-lab-post on a connection already open, which gives the guest's
# CLOCK_MONOTONIC as it sends and once answered; /out/moves.txt: "N/m sent_ns answered_ns" per
# move), then Ctrl-C. Writes /out/studio.json (the studio's exit status, the kernel driver before,
# during and after),
# /out/studio.log, /out/parameter.json (the studio's answer), /out/studio-state.json (its loop's state
# before Ctrl-C) and the device's logs.
. /lab/ffboard.sh
ip link set lo up
ffboard_plug --hand circle --extent "$CIRCLE_MM" --speed "$SPEED_MM_S" --at "$AT_X_MM" "$AT_Y_MM" || exit 1
driver_before=$(ffboard_interface_driver)
mkdir -p /tmp/studio
echo "spring $STIFFNESS" > /tmp/studio/spring.hmat
# shellcheck disable=SC2086
"$SANDPAPER" studio /tmp/studio/spring.hmat --device usb $LAB_RUN_GUARDS --listen 127.0.0.1:8000 > /out/studio.log 2>&1 &
studio_pid=$!

driver_during=
: > /out/moves.txt
if lab_wait_line /out/studio.log "^studio: http://" 60 && lab_wait_line "$FFB_DEVICE_LOG" "streaming" 60; then
  driver_during=$(ffboard_interface_driver)
  for value in $STIFFNESS_MOVES; do
    # sent_ns= and answered_ns= lines: the guest's CLOCK_MONOTONIC around the request.
    if "$LAB_POST" --port 8000 --path /api/parameter --warm /api/state --answer /out/parameter.json \
         --json "{\"name\": \"spring.stiffness\", \"value\": $value, \"unit\": \"N/m\"}" > /tmp/post.txt; then
      echo "$value $(sed -n 's/^sent_ns=//p' /tmp/post.txt) $(sed -n 's/^answered_ns=//p' /tmp/post.txt)" >> /out/moves.txt
    else
      echo "lab: the studio refused the parameter" >&2
    fi
    # Not a wait for readiness: how long each spring plays before the next move.
    sleep "$PLAY_AFTER_S"
  done
else
  echo "lab: the studio never played" >&2
fi
# The loop's state as the page sees it: whether it still plays, and a stop cause if it stopped.
wget -q -O /out/studio-state.json http://127.0.0.1:8000/api/state || echo "{}" > /out/studio-state.json
kill -INT "$studio_pid"
wait "$studio_pid"
studio_status=$?
ffboard_given_back
ffboard_stop
sed 's/^/studio: /' /out/studio.log
cat > /out/studio.json <<JSON
{"studio_status": $studio_status, "driver_before": "$driver_before",
 "driver_during": "$driver_during", "driver_after": "$DRIVER_AFTER", "input_after": "$INPUT_AFTER"}
JSON
cat /out/studio.json
