// A scene's pane (docs/STUDIO.md, "Scenes in 3-D"): the 3-D view, which is three.js and a bundle of
// its own (/scene3d.js, studio/CMakeLists.txt), loaded the first time a scene opens so that editing a
// material never loads it; the press depth, the buttons, and the readout of each touch's force.
import { api } from "./api.js";
import { $, setStatus } from "./page.js";
import { state } from "./state.js";

let loading = null, view = null, shownVersion = 0, busy = false, again = false;

function loadBundle() {
  loading ??= new Promise((resolve, reject) => {
    const s = document.createElement("script");
    s.src = "/scene3d.js";
    s.onload = () => resolve(window.sandpaperScene3d);
    s.onerror = () => { loading = null; reject(new Error("could not load the 3-D view's script (/scene3d.js)")); };
    document.head.append(s);
  });
  return loading;
}

// The press depth typed beside the view (mm), kept within 0 to 50 mm.
function pressDepthMm() {
  const v = Number($("#press-depth").value);
  return Number.isFinite(v) ? Math.min(Math.max(v, 0), 50) : 2;
}

const mm = (p) => p.map((v) => (v * 1e3).toFixed(2)).join(", ");

// Each touch's answer (POST /api/scene/device) in words and numbers; the arrow's scale in newtons.
function showTouch(t, mmPerN) {
  state.sceneTouch = t;
  $("#scene-force").textContent = t.force_magnitude_N.toFixed(3);
  $("#scene-normal-force").textContent = t.normal_force_N.toFixed(3);
  $("#scene-texture-force").textContent = Math.hypot(...t.texture_force_N).toFixed(3);
  // The relief (a normal-force texture) takes back the carve's share of the surface's press.
  $("#scene-relief").textContent = t.relief_carve_m === null || t.relief_carve_m === undefined ? "none"
    : `${Math.hypot(...t.relief_force_N).toFixed(3)} N, carve ${(t.relief_carve_m * 1e3).toFixed(3)} mm`;
  const where = t.in_contact ? `"${t.object}"${t.side ? ` ${t.side}` : ""}${t.sliding ? ", sliding" : ""}` : "free (no contact)";
  $("#scene-surface").textContent = where;
  $("#scene-material").textContent = !t.in_contact ? "" : t.material
    ? `${t.material}${t.material_name && t.material_name !== t.material ? ` (${t.material_name})` : ""}` : "(none: contact only)";
  $("#scene-device").textContent = mm(t.device_m);
  $("#scene-proxy").textContent = mm(t.proxy_m);
  $("#scene-scale").textContent = `force arrow: ${mmPerN} mm of the scene = 1 N`;
  document.body.dataset.sceneForce = t.force_magnitude_N.toFixed(3);
}

export function setupScene() {
  $("#scene-home").addEventListener("click", () => view?.home());
  $("#scene-lift").addEventListener("click", () => view?.lift());
}

// Shows the open scene's last good compile, fetching its geometry once per version (one fetch at a
// time, the newest last, as the 2-D preview does).
export async function refreshScene() {
  if (busy) { again = true; return; }
  busy = true;
  try {
    do {
      again = false;
      await refreshNow();
    } while (again);
  } catch (e) {
    setStatus(e.message, true);
  } finally {
    busy = false;
  }
}

async function refreshNow() {
  const version = state.sceneVersion;
  if (state.kind !== "scene" || !version || version === shownVersion) return;
  const lib = await loadBundle();
  if (!view) {
    view = lib.mount($("#scene-stage"), { api, setStatus, pressDepthMm, onTouch: showTouch });
    if (!view) return;
    window.studio.scene3d = view;  // for tests and scripts
  }
  const g = await api("GET", "/api/scene");
  if (state.kind !== "scene" || g.scene_version < shownVersion) return;
  shownVersion = g.scene_version;
  view.show(g);
  $("#scene-stage").dataset.version = shownVersion;
  $("#scene-caption").textContent = `${g.scene}: ${g.objects.length} object${g.objects.length === 1 ? "" : "s"}, ` +
    `${g.triangle_surfaces.length} triangles; compiled for ${g.device}. The frame is glTF's: x right, y up, z toward you.`;
}
