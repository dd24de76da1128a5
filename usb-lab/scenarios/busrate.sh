# How fast the lab's bus carries interrupt OUT reports: WRITES blocking writes of a 2-byte Device
# Control report with no bit set (the firmware does nothing with it) to the joystick's hidraw node,
# as fast as one shell loop issues them; the lab device logs each one's arrival (reports.csv).
# Writes /out/busrate.json (the guest-clock time the writes took). tools/usb-lab/run --bus-rate.
. /lab/ffboard.sh
ffboard_plug --hand scan --speed 10 --extent 10 || exit 1
node=/dev/$LAB_HIDRAW
lab_step "writing $WRITES reports to $node"
exec 3>"$node"
lab_now
t0=$LAB_NOW
i=0
# (busybox's printf is a shell builtin: one write(2) per report, no process per report)
while [ "$i" -lt "$WRITES" ]; do printf '\014\000' >&3 || break; i=$((i + 1)); done
lab_now
t1=$LAB_NOW
exec 3>&-
lab_step "$i writes in $((t1 - t0)) cs"
ffboard_stop
echo "{\"writes\": $i, \"elapsed_cs\": $((t1 - t0))}" > /out/busrate.json
