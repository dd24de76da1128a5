// The pointer on the stage: Dummy mode (the mouse moves the simulated hand), Shift-drag to pan a
// zoomed picture, and a workspace's patches dragged.
import { api } from "./api.js";
import { drawOverlay } from "./overlay.js";
import { $, setStatus } from "./page.js";
import { refreshPreview } from "./preview.js";
import { toMm } from "./stage.js";
import { state } from "./state.js";
import { workspacePointerDown, workspacePointerMove, workspacePointerUp } from "./workspace.js";
import { clampZoom, currentWindow } from "./zoom.js";

let handTimer = 0, handPending = null;
function sendHand(mm) {
  handPending = mm;
  if (handTimer) return;
  handTimer = setTimeout(async () => {
    handTimer = 0;
    const [x_mm, y_mm] = handPending;
    try { await api("POST", "/api/hand", { x_mm, y_mm }); } catch (e) { setStatus(e.message, true); }
  }, 20);
}

export function setupStage() {
  const stage = $("#stage");
  let dragging = false, pan = null;
  stage.addEventListener("pointerdown", (ev) => {
    if (state.kind === "workspace" && workspacePointerDown(ev)) return;
    stage.setPointerCapture(ev.pointerId);
    // Shift-drag pans the picture: the place under the pointer stays under it.
    if (ev.shiftKey && state.kind === "material" && state.patchMm) {
      pan = { at: toMm(ev), from: currentWindow() };
      return;
    }
    dragging = true;
    sendHand(toMm(ev));
  });
  stage.addEventListener("pointermove", (ev) => {
    if (state.kind === "workspace" && workspacePointerMove(ev)) return;
    if (pan) {
      const r = stage.getBoundingClientRect();
      const dx = ((ev.clientX - r.left) / r.width - 0.5) * pan.from.w + pan.from.cx - pan.at[0];
      const dy = (0.5 - (ev.clientY - r.top) / r.height) * pan.from.h + pan.from.cy - pan.at[1];
      state.zoom = clampZoom({ ...pan.from, cx: pan.from.cx - dx, cy: pan.from.cy - dy });
      // The picture follows the pointer until the studio draws the new window.
      $("#picture").style.transform = `translate(${(pan.from.cx - state.zoom.cx) / pan.from.w * r.width}px, ` +
        `${(state.zoom.cy - pan.from.cy) / pan.from.h * r.height}px)`;
      drawOverlay();
      return;
    }
    if (dragging || $("#follow").checked) sendHand(toMm(ev));
  });
  stage.addEventListener("pointerup", (ev) => {
    if (state.kind === "workspace" && workspacePointerUp(ev)) return;
    if (pan) {
      pan = null;
      refreshPreview();
      return;
    }
    dragging = false;
  });
}
