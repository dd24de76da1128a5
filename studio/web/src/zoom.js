// Zoom and pan over the whole patch: the window the studio draws a material's picture for.
import { $ } from "./page.js";
import { refreshPreview } from "./preview.js";
import { centreMm, toMm, windowMm } from "./stage.js";
import { state } from "./state.js";

// A window of the patch kept inside it (a window larger than the patch is centred), at least 0.05 mm.
export function clampZoom(z) {
  const [pw, ph] = state.patchMm || [z.w, z.h];
  const w = Math.min(Math.max(z.w, 0.05), pw), h = Math.min(Math.max(z.h, 0.05), ph);
  const cx = Math.min(Math.max(z.cx, -pw / 2 + w / 2), pw / 2 - w / 2);
  const cy = Math.min(Math.max(z.cy, -ph / 2 + h / 2), ph / 2 - h / 2);
  return { cx, cy, w, h };
}
function setZoom(z) {
  state.zoom = z && clampZoom(z);
  refreshPreview();
}
export function currentWindow() {
  const [w, h] = windowMm(), [cx, cy] = centreMm();
  return { cx, cy, w, h };
}
// Zooms by `factor` (> 1: in) keeping the place under (xMm, yMm) where it is on the stage.
function zoomAbout(factor, xMm, yMm) {
  const z = currentWindow();
  const w = z.w / factor, h = z.h / factor;
  setZoom({ cx: xMm - (xMm - z.cx) / factor, cy: yMm - (yMm - z.cy) / factor, w, h });
}
export function setupZoom() {
  $("#zoom-whole").addEventListener("click", () => state.patchMm && setZoom({ cx: 0, cy: 0, w: state.patchMm[0], h: state.patchMm[1] }));
  $("#zoom-in").addEventListener("click", () => { const z = currentWindow(); zoomAbout(2, z.cx, z.cy); });
  $("#zoom-out").addEventListener("click", () => { const z = currentWindow(); zoomAbout(0.5, z.cx, z.cy); });
  $("#zoom-reset").addEventListener("click", () => setZoom(null));
  $("#stage").addEventListener("wheel", (ev) => {
    if (state.kind !== "material" || !state.patchMm) return;
    ev.preventDefault();
    const [x, y] = toMm(ev);
    zoomAbout(ev.deltaY < 0 ? 1.25 : 0.8, x, y);
  }, { passive: false });
}
