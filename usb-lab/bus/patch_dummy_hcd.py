#!/usr/bin/env python3
"""The lab's change to Linux's dummy_hcd.c (drivers/usb/gadget/udc/, as Debian's linux-source-6.1
ships it): frames a real bus would have. The stock module runs its transfer loop on an hrtimer every
125 us (a high-speed microframe) at every speed and does not honour bInterval (its own FIXME), so an
interrupt endpoint of a full-speed device may move up to 8 transactions a millisecond; a real
full-speed bus moves one per 1 ms frame at bInterval 1 (USB 2.0 sections 5.7.4 and 9.6.6). Changed:

- the loop runs once per 1 ms frame for low- and full-speed devices (125 us microframes stay for
  high speed and above);
- an interrupt endpoint takes at most one transaction per urb->interval frames (frames at low and
  full speed, microframes at high speed), counted by the loop itself;
- for the lab's test, read-only module parameters: usb_lab_frames (frames run) and
  usb_lab_min_frame_gap_ns (the shortest time between the starts of two frames, the second scheduled
  a frame ahead).

Made by substitution at named places (each must be found exactly once, or this fails saying which),
so the project carries no copy of the kernel's text. docs/USB_PID.md "The lab's bus".

  patch_dummy_hcd.py IN.c OUT.c
"""
from __future__ import annotations

import sys

FRAME_HELPER = """
/* usb-lab: frames run since the module was loaded, all host controllers together, for the lab's
 * test of the frame rate (/sys/module/dummy_hcd/parameters/usb_lab_frames). */
static unsigned long usb_lab_frames;
module_param(usb_lab_frames, ulong, 0444);
MODULE_PARM_DESC(usb_lab_frames, "usb-lab: bus frames run (read-only)");

/* usb-lab: the shortest time from one frame's start to the next's, over the frames scheduled one
 * frame ahead (an unlink or a resume runs the loop at once, as the stock module does). ns; 0: none yet. */
static unsigned long usb_lab_min_frame_gap_ns;
module_param(usb_lab_min_frame_gap_ns, ulong, 0444);
MODULE_PARM_DESC(usb_lab_min_frame_gap_ns, "usb-lab: shortest frame start to frame start, ns (read-only)");

static void usb_lab_arm(struct dummy_hcd *dum_hcd)
{
	dum_hcd->usb_lab_armed = 1;
}

static void usb_lab_frame_started(struct dummy_hcd *dum_hcd)
{
	ktime_t now = ktime_get();

	if (dum_hcd->usb_lab_armed && dum_hcd->usb_lab_frame > 1) {
		unsigned long gap = (unsigned long)ktime_to_ns(ktime_sub(now, dum_hcd->usb_lab_start));

		if (!usb_lab_min_frame_gap_ns || gap < usb_lab_min_frame_gap_ns)
			WRITE_ONCE(usb_lab_min_frame_gap_ns, gap);
	}
	dum_hcd->usb_lab_armed = 0;
	dum_hcd->usb_lab_start = now;
	WRITE_ONCE(usb_lab_frames, usb_lab_frames + 1);
}

/* usb-lab: one transfer loop per bus frame, as a real bus has (1 ms below high speed). */
static u64 usb_lab_frame_ns(const struct dummy_hcd *dum_hcd)
{
	switch (dum_hcd->dum->gadget.speed) {
	case USB_SPEED_LOW:
	case USB_SPEED_FULL:
		return 1000000;
	default:
		return DUMMY_TIMER_INT_NSECS;
	}
}
"""

# (what to find, what it becomes, how many times it must be there)
EDITS = [
    # A frame counter in the host controller and, per endpoint, the frame of its last interrupt transaction.
    ("\tunsigned\t\t\ttimer_pending:1;\n",
     "\tunsigned long\t\t\tusb_lab_frame;\n\tktime_t\t\t\t\tusb_lab_start;\n"
     "\tunsigned\t\t\tusb_lab_armed:1;\n\tunsigned\t\t\ttimer_pending:1;\n", 1),
    ("\tunsigned\t\t\talready_seen:1;\n",
     "\tunsigned long\t\t\tusb_lab_last_frame;\n\tunsigned\t\t\tusb_lab_moved:1;\n\tunsigned\t\t\talready_seen:1;\n", 1),
    # Every place the loop is scheduled one frame ahead.
    ("hrtimer_start(&dum_hcd->timer, ns_to_ktime(DUMMY_TIMER_INT_NSECS),",
     "usb_lab_arm(dum_hcd), hrtimer_start(&dum_hcd->timer, ns_to_ktime(usb_lab_frame_ns(dum_hcd)),", 2),
    # Each run of the loop is a frame.
    ("\tdum_hcd->next_frame_urbp = NULL;\n",
     "\tdum_hcd->next_frame_urbp = NULL;\n\tdum_hcd->usb_lab_frame++;\n\tusb_lab_frame_started(dum_hcd);\n", 1),
    # An interrupt endpoint waits out its interval since its last transaction.
    ("\t\tcase PIPE_INTERRUPT:\n",
     "\t\tcase PIPE_INTERRUPT:\n"
     "\t\t\tif (ep->usb_lab_moved && dum_hcd->usb_lab_frame - ep->usb_lab_last_frame <\n"
     "\t\t\t\t\t(unsigned long)max(urb->interval, 1))\n"
     "\t\t\t\tcontinue;\n"
     "\t\t\tep->usb_lab_moved = 1;\n"
     "\t\t\tep->usb_lab_last_frame = dum_hcd->usb_lab_frame;\n", 1),
]
# The helper goes before the first function that schedules the loop.
HELPER_BEFORE = "static int dummy_urb_enqueue("


def patch(text: str) -> str:
    for old, new, count in EDITS:
        found = text.count(old)
        if found != count:
            raise SystemExit(f"patch_dummy_hcd: expected {count} of {old.strip()!r}, found {found}: "
                             "not the dummy_hcd.c this patch was written for (Debian's 6.1)")
        text = text.replace(old, new)
    if text.count(HELPER_BEFORE) != 1:
        raise SystemExit(f"patch_dummy_hcd: {HELPER_BEFORE!r} not found once")
    return text.replace(HELPER_BEFORE, FRAME_HELPER.lstrip("\n") + "\n" + HELPER_BEFORE)


def main() -> int:
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    src = open(sys.argv[1], encoding="utf-8").read()
    with open(sys.argv[2], "w", encoding="utf-8") as f:
        f.write(patch(src))
    return 0


if __name__ == "__main__":
    sys.exit(main())
