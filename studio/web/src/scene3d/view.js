// The studio's 3-D view of a scene (docs/STUDIO.md, "Scenes in 3-D"), bundled apart from the page
// (studio/CMakeLists.txt) and loaded by it when a scene opens (../scene.js): three.js' WebGL renderer,
// the scene's meshes coloured by surface, an orbiting camera, and the 3-D Dummy mode's device, proxy
// and force. It imports nothing of the page: what it needs comes in `host` ({ api, setStatus,
// pressDepthMm() }), and it shows itself as window.sandpaperScene3d.
import { AmbientLight, Color, DirectionalLight, MOUSE, PerspectiveCamera, Scene, Vector3, WebGLRenderer } from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { DummyMode } from "./dummy.js";
import { Markers } from "./markers.js";
import { disposeMesh, sceneMesh } from "./meshes.js";

const BACKGROUND = "#f4f4f1";

class SceneView {
  constructor(container, host) {
    this.container = container;
    this.host = host;
    // Throws where the browser has no WebGL; mount() says so in the view.
    this.renderer = new WebGLRenderer({ antialias: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.canvas = this.renderer.domElement;
    this.canvas.setAttribute("aria-label", "the scene in 3-D: left-drag on a surface presses the device into it");
    container.append(this.canvas);
    this.scene = new Scene();
    this.scene.background = new Color(BACKGROUND);
    this.camera = new PerspectiveCamera(40, 4 / 3, 0.001, 100);
    // The light comes from over the viewer's shoulder wherever the camera goes.
    const key = new DirectionalLight(0xffffff, 2.2);
    key.position.set(0.4, 0.8, 1);
    this.camera.add(key);
    this.scene.add(this.camera, new AmbientLight(0xffffff, 0.9));
    // The left button is the hand's (Dummy mode): the camera orbits on the right button (or Alt and
    // the left), pans with Shift and the right, and zooms on the wheel.
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.mouseButtons = { LEFT: null, MIDDLE: MOUSE.DOLLY, RIGHT: MOUSE.ROTATE };
    this.canvas.addEventListener("pointerdown", (ev) => { this.controls.mouseButtons.LEFT = ev.altKey ? MOUSE.ROTATE : null; }, true);
    this.controls.addEventListener("change", () => this.draw());
    this.dummy = new DummyMode(this.canvas, this.camera, host, (t) => this.touched(t));
    this.touch = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth), h = Math.max(1, Math.round(w * 0.75));
    this.renderer.setSize(w, h, false);
    this.canvas.style.width = "100%";
    this.canvas.style.height = "auto";
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.draw();
  }

  // A scene's geometry (GET /api/scene): replaces what was shown. The camera is framed on the first
  // scene, and kept where the user left it while the same scene's text is edited.
  show(g) {
    const sameFile = this.geometry && this.geometry.file === g.file;
    if (this.mesh) this.scene.remove(this.mesh);
    disposeMesh(this.mesh);
    if (this.markers) { this.scene.remove(this.markers.group); this.markers.dispose(); }
    this.geometry = g;
    this.mesh = sceneMesh(g);
    this.dummy.mesh = this.mesh;
    const min = new Vector3(...g.bounds_m.min), max = new Vector3(...g.bounds_m.max);
    this.size_m = Math.max(min.distanceTo(max), 1e-3);
    this.markers = new Markers(this.size_m);
    this.scene.add(this.mesh, this.markers.group);
    if (!sameFile) this.home();
    this.touched(g.touch);
  }

  // The whole scene in view, seen from the front, the right and above (as `sandpaper preview` draws
  // it), as large as its bounding box allows: the distance that fits the bounding sphere leaves a flat
  // scene (a ball on a table) small, so it is brought in until the box's corners reach 90 % of the view.
  home() {
    const g = this.geometry;
    if (!g) return;
    const min = new Vector3(...g.bounds_m.min), max = new Vector3(...g.bounds_m.max);
    const centre = min.clone().add(max).multiplyScalar(0.5);
    const towardViewer = new Vector3(0.45, 0.55, 1).normalize();
    let distance = this.size_m / 2 / Math.sin((this.camera.fov * Math.PI) / 360);
    const place = () => {
      this.camera.near = distance / 200;
      this.camera.far = distance * 20;
      this.camera.position.copy(centre).addScaledVector(towardViewer, distance);
      this.camera.lookAt(centre);
      this.camera.updateProjectionMatrix();
      this.camera.updateMatrixWorld();
    };
    for (let i = 0; i < 3; i++) {  // the view's size goes nearly as 1 / distance: three steps settle it
      place();
      let reach = 0;
      for (let c = 0; c < 8; c++) {
        const p = new Vector3(c & 1 ? max.x : min.x, c & 2 ? max.y : min.y, c & 4 ? max.z : min.z).project(this.camera);
        reach = Math.max(reach, Math.abs(p.x), Math.abs(p.y));
      }
      distance *= Math.min(Math.max(reach / 0.9, 0.5), 2);
    }
    place();
    this.controls.target.copy(centre);
    this.controls.update();
    this.draw();
  }

  // Lifts the device off the surface it presses (10 mm along the contact's normal).
  lift() { this.dummy.lift(this.touch); }

  touched(t) {
    if (!t || !this.markers) return;
    this.touch = t;
    this.markers.show(t);
    this.draw();
    this.host.onTouch?.(t, this.markers.mmPerN);
  }

  // Drawn on the next frame, once however many changes asked for it.
  draw() {
    if (this.frame) return;
    this.frame = requestAnimationFrame(() => {
      this.frame = 0;
      this.renderer.render(this.scene, this.camera);
    });
  }

  // For tests and scripts (window.studio.scene3d). The page point (client px) where a scene point (m) is drawn.
  screenOf(p) {
    const v = new Vector3(...p).project(this.camera);
    const r = this.canvas.getBoundingClientRect();
    return [r.left + ((v.x + 1) / 2) * r.width, r.top + ((1 - v.y) / 2) * r.height];
  }

  // Draws now and counts the pixels that are not the background, and those the force arrow changes
  // (drawn again without it): proof that WebGL drew the scene and the arrow, read from the canvas.
  pixels() {
    const gl = this.renderer.getContext();
    const read = () => {
      this.renderer.render(this.scene, this.camera);
      const px = new Uint8Array(gl.drawingBufferWidth * gl.drawingBufferHeight * 4);
      gl.readPixels(0, 0, gl.drawingBufferWidth, gl.drawingBufferHeight, gl.RGBA, gl.UNSIGNED_BYTE, px);
      return px;
    };
    // getHex() is sRGB, as the canvas holds it (Color's r, g, b are linear).
    const bg = new Color(BACKGROUND).getHex();
    const [r0, g0, b0] = [bg >> 16, (bg >> 8) & 255, bg & 255];
    const withArrow = read();
    const shown = this.markers?.arrow.visible;
    if (this.markers) this.markers.arrow.visible = false;
    const without = read();
    if (this.markers) this.markers.arrow.visible = shown;
    this.renderer.render(this.scene, this.camera);
    let painted = 0, arrow = 0;
    for (let i = 0; i < withArrow.length; i += 4) {
      if (Math.abs(withArrow[i] - r0) + Math.abs(withArrow[i + 1] - g0) + Math.abs(withArrow[i + 2] - b0) > 12) painted++;
      if (withArrow[i] !== without[i] || withArrow[i + 1] !== without[i + 1] || withArrow[i + 2] !== without[i + 2]) arrow++;
    }
    return { width: gl.drawingBufferWidth, height: gl.drawingBufferHeight, painted, arrow };
  }

  arrow() {
    const m = this.markers;
    return m ? { visible: m.arrow.visible, length_m: m.lengthDrawn_m, mm_per_N: m.mmPerN } : null;
  }
}

// The page's entry: the view in `container`, or null with the reason written there when WebGL fails.
function mount(container, host) {
  try {
    return new SceneView(container, host);
  } catch (e) {
    container.textContent = `This browser cannot draw the 3-D view (WebGL: ${e.message}). ` +
      "The scene still compiles; its API (GET /api/scene, POST /api/scene/device) still answers.";
    return null;
  }
}

window.sandpaperScene3d = { mount };
