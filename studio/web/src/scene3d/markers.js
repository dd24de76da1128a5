// What the 3-D Dummy mode draws over the scene: the simulated device point (drawn through the
// surface it is pressed into), the proxy on the surface, the spring between them, and the force on the
// device as an arrow from the proxy, its length proportional to newtons at a stated scale.
import { ArrowHelper, BufferGeometry, Group, Line, LineBasicMaterial, Mesh, MeshBasicMaterial, SphereGeometry, Vector3 } from "three";

// The 2-D Dummy mode's colours (overlay.js): the hand yellow, the force red.
const DEVICE = 0xffd23c, PROXY = 0x222222, FORCE = 0xc0392b;

// A length for the arrow's scale: 1, 2 or 5 times a power of ten, at most `mm`.
function roundDown125(mm) {
  const p = 10 ** Math.floor(Math.log10(mm));
  return [5, 2, 1].map((k) => k * p).find((v) => v <= mm) || p;
}

export class Markers {
  // `size_m`: the scene's bounding-box diagonal, which sets the markers' size and the arrow's scale.
  constructor(size_m) {
    this.group = new Group();
    const r = Math.max(size_m * 0.008, 1e-4);
    // Drawn last and through everything: the device sits inside the surface it presses.
    this.device = new Mesh(new SphereGeometry(r, 20, 12), new MeshBasicMaterial({ color: DEVICE, depthTest: false, transparent: true, opacity: 0.9 }));
    this.device.renderOrder = 10;
    this.proxy = new Mesh(new SphereGeometry(r * 0.7, 20, 12), new MeshBasicMaterial({ color: PROXY }));
    this.spring = new Line(new BufferGeometry().setFromPoints([new Vector3(), new Vector3()]),
                           new LineBasicMaterial({ color: PROXY, depthTest: false, transparent: true }));
    this.spring.renderOrder = 9;
    // The arrow: 8 % of the scene's size for each newton, rounded down to 1, 2 or 5 mm times a power of ten.
    this.mmPerN = roundDown125(size_m * 1e3 * 0.08);
    this.arrow = new ArrowHelper(new Vector3(0, 1, 0), new Vector3(), 1, FORCE);
    this.arrow.renderOrder = 11;
    for (const m of [this.arrow.line.material, this.arrow.cone.material]) m.depthTest = false;
    this.arrow.visible = false;
    this.group.add(this.proxy, this.spring, this.device, this.arrow);
  }

  // A touch's answer (POST /api/scene/device): where everything is, and the force.
  show(t) {
    const device = new Vector3(...t.device_m), proxy = new Vector3(...t.proxy_m), force = new Vector3(...t.force_N);
    this.device.position.copy(device);
    this.proxy.position.copy(proxy);
    this.proxy.visible = t.in_contact;
    this.spring.geometry.setFromPoints([proxy, device]);
    this.spring.visible = t.in_contact;
    const n = force.length();
    this.arrow.visible = n > 1e-6;
    if (this.arrow.visible) {
      const length_m = n * this.mmPerN * 1e-3;
      this.arrow.position.copy(proxy);
      this.arrow.setDirection(force.clone().normalize());
      // The head never longer than half the arrow, so a small force still shows its shaft; broad,
      // since WebGL draws the shaft one pixel wide.
      const head = Math.min(length_m * 0.5, this.mmPerN * 1e-3 * 0.35);
      this.arrow.setLength(length_m, head, head * 0.6);
    }
    this.lengthDrawn_m = this.arrow.visible ? n * this.mmPerN * 1e-3 : 0;
  }

  dispose() {
    this.group.traverse((o) => { o.geometry?.dispose(); o.material?.dispose(); });
  }
}
