// The 3-D Dummy mode (Minsky 1995's Dummy mode, in 3-D): a left-drag on a surface moves the simulated
// device to the point under the mouse, pressed into the surface by the press depth along its inward
// normal, and posts it to the studio (POST /api/scene/device), whose contact renderer answers with the
// proxy and the force. Pressing starts a new touch (the proxy put down just above the point); dragging
// then moves the device with the proxy following over the surface, friction and texture included.
import { Raycaster, Vector2 } from "three";

// Where a new touch's proxy starts: this far above the surface along its normal (m).
const LIFT_M = 1e-3;

export class DummyMode {
  // `host`: { api, setStatus, pressDepthMm() }; `onAnswer(t)` is given each answer.
  constructor(canvas, camera, host, onAnswer) {
    Object.assign(this, { canvas, camera, host, onAnswer, mesh: null, dragging: false, pending: null, sending: null });
    this.ray = new Raycaster();
    canvas.addEventListener("pointerdown", (ev) => {
      // Left button only; Alt-drag orbits (view.js), as the right button does.
      if (ev.button !== 0 || ev.altKey) return;
      const hit = this.hit(ev);
      if (!hit) return;
      this.dragging = true;
      this.send(this.pressed(hit), hit.point.clone().addScaledVector(hit.normal, LIFT_M).toArray());
    });
    canvas.addEventListener("pointermove", (ev) => {
      if (!this.dragging) return;
      const hit = this.hit(ev);
      if (hit) this.send(this.pressed(hit));
    });
    for (const end of ["pointerup", "pointercancel"]) canvas.addEventListener(end, () => { this.dragging = false; });
  }

  // The first surface under the mouse seen from the side it is felt from (a face's outside, where its
  // triangle winds counter-clockwise): {point, normal}, or null.
  hit(ev) {
    if (!this.mesh) return null;
    const r = this.canvas.getBoundingClientRect();
    this.ray.setFromCamera(new Vector2(((ev.clientX - r.left) / r.width) * 2 - 1, 1 - ((ev.clientY - r.top) / r.height) * 2), this.camera);
    for (const h of this.ray.intersectObject(this.mesh, false)) {
      if (h.face.normal.dot(this.ray.ray.direction) < 0) return { point: h.point, normal: h.face.normal.clone() };
    }
    return null;
  }

  pressed(hit) {
    return hit.point.clone().addScaledVector(hit.normal, -this.host.pressDepthMm() * 1e-3).toArray();
  }

  // One request on the wire at a time, the newest point next: a fast drag skips points rather than
  // queueing them. A new touch's starting point is kept if a move replaces it before it is sent.
  send(device_m, from_m) {
    this.pending = { device_m, from_m: from_m || this.pending?.from_m };
    if (!this.sending) this.sending = this.flush();
  }

  async flush() {
    try {
      while (this.pending) {
        const body = this.pending;
        this.pending = null;
        if (!body.from_m) delete body.from_m;
        try {
          this.onAnswer(await this.host.api("POST", "/api/scene/device", body));
        } catch (e) {
          this.host.setStatus(e.message, true);
        }
      }
    } finally {
      this.sending = null;
    }
  }

  // Lifts the device off the surface along the contact's normal (10 mm): nothing is felt.
  lift(t) {
    if (!t?.in_contact) return;
    const [p, n] = [t.proxy_m, t.normal];
    this.send(p.map((v, i) => v + n[i] * 0.01));
  }
}
