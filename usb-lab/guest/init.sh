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

export LAB_OUT=/out LAB_IN=/in LAB_GADGET=/lab/gadget.sh
read -r uptime _ < /proc/uptime
echo "LAB-SCENARIO-START uptime=$uptime"
cd /lab && sh /lab/scenario.sh
status=$?
sync
umount /out 2>/dev/null
echo "LAB-EXIT-STATUS $status"
poweroff -f
