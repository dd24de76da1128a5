// The workspace canvas: a workspace's patches drawn on the stage, moved and resized by dragging.
import { api } from "./api.js";
import { setText } from "./editor.js";
import { hooks } from "./hooks.js";
import { $, roughnessText, setStatus } from "./page.js";
import { fitStage, toMm, toPx } from "./stage.js";
import { state } from "./state.js";

let wsDrag = null;
export function drawWorkspace() {
  const ws = state.workspace;
  const layer = $("#patches");
  layer.replaceChildren();
  $("#picture").hidden = true;
  $("#scan").innerHTML = "";
  if (!ws || !ws.patches) return;
  fitStage();
  $("#picture-caption").textContent = `${ws.name || ""}: ${ws.patches.length} patches on ${ws.size_mm[0].toFixed(1)} × ` +
    `${ws.size_mm[1].toFixed(1)} mm, back to front; drag a patch to move it, its corner to resize it`;
  const r = $("#stage").getBoundingClientRect();
  ws.patches.forEach((p, i) => {
    const d = document.createElement("div");
    d.className = "patch" + (i === state.selected ? " selected" : "");
    d.dataset.index = i;
    const [x0, y0] = toPx(p.centre_mm[0] - p.size_mm[0] / 2, p.centre_mm[1] + p.size_mm[1] / 2, r);
    const [x1, y1] = toPx(p.centre_mm[0] + p.size_mm[0] / 2, p.centre_mm[1] - p.size_mm[1] / 2, r);
    Object.assign(d.style, { left: `${x0}px`, top: `${y0}px`, width: `${x1 - x0}px`, height: `${y1 - y0}px`, zIndex: 1 + i });
    // Thesis Appendix B: Normal shows each patch's shaded height map, Depth its surface as data (here
    // the force field, the program's own gradient), Blind black rectangles only.
    if (state.mode === "blind") d.classList.add("blind");
    else d.style.backgroundImage = `url(/api/preview/patch-${i}${state.mode === "depth" ? "-field" : ""}.png?v=${state.version})`;
    d.title = `${p.source}: ${p.compiled_max_lateral_force_N.toFixed(3)} N, roughness ${roughnessText(p.compiled_roughness)}`;
    if (state.mode !== "blind") {
      const label = document.createElement("span");
      label.textContent = p.source;
      d.append(label);
    }
    const grip = document.createElement("i");
    grip.className = "grip";
    d.append(grip);
    layer.append(d);
  });
}

export function workspacePointerDown(ev) {
  const patch = ev.target.closest(".patch");
  if (!patch || !ev.shiftKey && !ev.target.classList.contains("grip") && !$("#edit-patches").checked) return false;
  const i = Number(patch.dataset.index);
  state.selected = i;
  const p = state.workspace.patches[i];
  wsDrag = { i, resize: ev.target.classList.contains("grip"), start: toMm(ev), centre: [...p.centre_mm], size: [...p.size_mm] };
  $("#stage").setPointerCapture(ev.pointerId);
  drawWorkspace();
  return true;
}
export function workspacePointerMove(ev) {
  if (!wsDrag) return false;
  const [x, y] = toMm(ev);
  const p = state.workspace.patches[wsDrag.i];
  const dx = x - wsDrag.start[0], dy = y - wsDrag.start[1];
  if (wsDrag.resize) {
    p.size_mm = [Math.max(2, wsDrag.size[0] + dx), Math.max(2, wsDrag.size[1] - dy)];
    p.centre_mm = [wsDrag.centre[0] + (p.size_mm[0] - wsDrag.size[0]) / 2, wsDrag.centre[1] - (p.size_mm[1] - wsDrag.size[1]) / 2];
  } else {
    p.centre_mm = [wsDrag.centre[0] + dx, wsDrag.centre[1] + dy];
  }
  drawWorkspace();
  return true;
}
export async function workspacePointerUp() {
  if (!wsDrag) return false;
  const p = state.workspace.patches[wsDrag.i];
  const round = (v) => Math.round(v * 10) / 10;
  wsDrag = null;
  try {
    const r = await api("POST", "/api/workspace/patch", { index: p.index, x_mm: round(p.centre_mm[0]), y_mm: round(p.centre_mm[1]),
      width_mm: round(p.size_mm[0]), height_mm: round(p.size_mm[1]) });
    setText(r.text);
    hooks.applyCompile(r);
  } catch (e) {
    setStatus(e.message, true);
  }
  return true;
}
