// Compiling the typed text (POST /api/material) and applying a compile's answer to the whole page.
import { api } from "./api.js";
import { showDiagnostics } from "./diagnostics.js";
import { editor } from "./editor.js";
import { markUnsaved } from "./file-list.js";
import { $, roughnessText, setStatus } from "./page.js";
import { refreshPreview } from "./preview.js";
import { refreshScene } from "./scene.js";
import { renderSliders } from "./sliders.js";
import { state } from "./state.js";

export function compileNow() {
  state.compileTimer = 0;
  const text = editor.state.doc.toString();
  const t0 = performance.now();
  // Remembered, so that opening another file waits for it: posted after the open, it would become
  // the other file's text.
  state.sentText = text;
  // One compile on the wire at a time, in the order typed: two requests in flight can reach the
  // studio in either order, and an older text landing last would become the studio's text (and,
  // followed back, replace what was typed since).
  const before = state.compiling;
  const sent = (async () => {
    try {
      await before;
      if (editor.state.doc.toString() !== text) return;  // typed on meanwhile: the later compile sends it
      const r = await api("POST", "/api/material", text, false);
      if (editor.state.doc.toString() !== text) return;  // typed on meanwhile: the next compile answers
      state.lastCompileMs = performance.now() - t0;
      applyCompile(r);
    } catch (e) {
      setStatus(e.message, true);
    }
  })();
  state.compiling = sent;
  return sent;
}

export function applyCompile(r) {
  showDiagnostics(r.diagnostics || []);
  document.body.dataset.compiles = r.ok ? "yes" : "no";
  $("#stale").textContent = r.version
    ? `the last good picture (v${r.version}, still playing): this text does not compile`
    : "nothing has compiled yet: this text does not compile";
  $("#compile-state").title = $("#compile-state").textContent = r.ok
    ? `compiled: ${r.material || (r.scene ? sceneSummary(r.scene) : workspaceSummary(r.workspace))}` +
      (r.compiled_max_lateral_force_N !== undefined ? ` · ${r.compiled_max_lateral_force_N.toFixed(3)} N, roughness ${roughnessText(r.compiled_roughness)}` : "")
    : state.kind === "scene" ? "does not compile: the view shows the last good scene"
    : "does not compile: the last good program keeps playing";
  $("#saved").textContent = r.saved ? "saved" : "unsaved";
  markUnsaved(state.file, !r.saved);
  state.version = r.version;
  if (r.ok && r.size_m) state.patchMm = [r.size_m[0] * 1e3, r.size_m[1] * 1e3];
  if (r.text_version !== undefined) state.textVersion = Math.max(state.textVersion || 0, r.text_version);
  if (r.scene_version !== undefined) state.sceneVersion = r.scene_version;
  renderSliders(r.parameters || []);
  if (r.ok) (state.kind === "scene" ? refreshScene() : refreshPreview());
}

// A scene's compile (GET /api/current, POST /api/material): its name, objects and triangles.
function sceneSummary(s) {
  return `scene ${s.scene} · ${s.objects} object${s.objects === 1 ? "" : "s"}, ${s.triangles} triangles`;
}

// A workspace's compile (schema::to_json of the program): its name, patches and size.
function workspaceSummary(ws) {
  if (!ws) return "";
  const n = ws.patch_count ?? ws.patches?.length ?? 0;
  const size = ws.size_m ? ` on ${(ws.size_m[0] * 1e3).toFixed(1)} × ${(ws.size_m[1] * 1e3).toFixed(1)} mm` : "";
  return `${ws.workspace || "workspace"} · ${n} patch${n === 1 ? "" : "es"}${size}`;
}

export async function flushCompile() {
  if (state.compileTimer) { clearTimeout(state.compileTimer); await compileNow(); }
}
