#!/bin/sh
# PID 1 of the USB lab's guest (busybox sh): brings up what the scenario needs, runs
# /lab/scenario.sh, says how it ended on a marker line the host reads, and powers off. PID 1 must
# never exit (the kernel would panic), so every step that can fail only reports it.
export PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root
mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
mkdir -p /dev/pts /dev/shm
mount -t devpts devpts /dev/pts
mount -t tmpfs tmpfs /dev/shm
# /tmp stays the initramfs's own (writable) directory: binaries given from host /tmp live there.

while read -r ko params; do
  # shellcheck disable=SC2086  # the parameters are words
  insmod "$ko" $params || echo "lab: insmod $ko $params failed"
done < /lab/modules
mount -t configfs configfs /sys/kernel/config || echo "lab: configfs did not mount"

# The host says on the kernel command line which shared folders it attached (lab.out=1, lab.in=1).
cmdline=$(cat /proc/cmdline)
case " $cmdline " in *" lab.out=1 "*)
  mount -t 9p -o trans=virtio,version=9p2000.L,msize=524288 labout /out \
    || echo "lab: the output folder did not mount";;
esac
case " $cmdline " in *" lab.in=1 "*)
  mount -t 9p -o trans=virtio,version=9p2000.L,msize=524288,ro,cache=loose labin /in \
    || echo "lab: the input folder did not mount";;
esac

# What every process is doing, printed when the scenario outlives the host's patience: the host
# only sees the console, and a guest killed at its timeout would otherwise say nothing about where
# it stood. The kernel stack (wchan, /proc/PID/stack) names a wait in a driver; the log's tail
# names what the kernel said at debug level meanwhile.
lab_hang_report() {
  local p t name state user
  echo "lab: the scenario has run $1 s of guest time; what each process is doing:"
  for p in /proc/[0-9]*; do
    # Kernel threads (no command line) only when they wait uninterruptibly (D): a stuck driver.
    user=$(head -c 1 "$p/cmdline" 2>/dev/null | wc -c)
    for t in "$p"/task/[0-9]*; do
      read -r name < "$t/comm" 2>/dev/null || continue
      state=$(sed -n 's/^State:[[:space:]]*//p' "$t/status" 2>/dev/null)
      [ "$user" -gt 0 ] || [ "${state%% *}" = D ] || continue
      echo "lab: pid ${p##*/} task ${t##*/} $name [$state] in $(cat "$t/wchan" 2>/dev/null)"
      sed 's/^/lab:     /' "$t/stack" 2>/dev/null | head -n 12
    done
  done
  echo "lab: the kernel log's last lines:"
  dmesg | tail -n 40 | sed 's/^/lab: kernel: /'
}
report_after=
for word in $cmdline; do
  case $word in lab.report_after=*) report_after=${word#lab.report_after=} ;; esac
done

export LAB_OUT=/out LAB_IN=/in LAB_GADGET=/lab/gadget.sh
read -r uptime _ < /proc/uptime
echo "LAB-SCENARIO-START uptime=$uptime"
cd /lab && sh /lab/scenario.sh &
scenario=$!
reporter=
if [ -n "$report_after" ]; then
  # A timer, not a wait for an event: it only speaks if the scenario is still running.
  ( sleep "$report_after" && kill -0 "$scenario" 2>/dev/null && lab_hang_report "$report_after" ) &
  reporter=$!
fi
wait "$scenario"
status=$?
[ -n "$reporter" ] && kill "$reporter" 2>/dev/null
sync
umount /out 2>/dev/null
echo "LAB-EXIT-STATUS $status"
poweroff -f
