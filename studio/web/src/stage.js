// Where things are on the stage, for the preview, the overlay, zoom, the pointer and the workspace alike.
import { $ } from "./page.js";
import { state } from "./state.js";

// Stage pixels <-> millimetres: the picture covers window_mm centred on the patch centre (material),
// or on the zoom's centre, or the workspace's rectangle (workspace); y up.
export function windowMm() {
  if (state.kind === "workspace") return state.workspace?.size_mm || [228.6, 228.6];
  if (state.zoom) return [state.zoom.w, state.zoom.h];
  return state.preview?.window_mm || [80, 80];
}
export function centreMm() {
  return state.kind === "material" && state.zoom ? [state.zoom.cx, state.zoom.cy] : [0, 0];
}
// The stage takes the shape of what it shows, so that a picture is never stretched (a 60 x 39.8 mm
// photograph is drawn 3:2, not square) and pixels map to millimetres alike across and down.
export function fitStage() {
  const [w, h] = windowMm();
  if (w > 0 && h > 0) $("#stage").style.aspectRatio = `${w} / ${h}`;
}
export function toMm(ev) {
  const r = $("#stage").getBoundingClientRect();
  const [w, h] = windowMm(), [cx, cy] = centreMm();
  return [cx + ((ev.clientX - r.left) / r.width - 0.5) * w, cy + (0.5 - (ev.clientY - r.top) / r.height) * h];
}
export function toPx(xMm, yMm, r) {
  const [w, h] = windowMm(), [cx, cy] = centreMm();
  return [((xMm - cx) / w + 0.5) * r.width, (0.5 - (yMm - cy) / h) * r.height];
}
