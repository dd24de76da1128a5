// The preview of what plays: the studio's pictures of a material (its own window or a zoomed one) and
// its scan line, or the workspace; one refresh at a time.
import { api } from "./api.js";
import { drawOverlay } from "./overlay.js";
import { $, setStatus } from "./page.js";
import { fitStage } from "./stage.js";
import { state } from "./state.js";
import { drawWorkspace } from "./workspace.js";

// One refresh at a time, the latest version last: a browser has six connections to the studio, and
// pictures waiting for their render must not hold them all while a slider's edits queue behind them.
let previewBusy = false, previewAgain = false;
export async function refreshPreview() {
  if (previewBusy) { previewAgain = true; return; }
  previewBusy = true;
  try {
    do { previewAgain = false; await refreshPreviewNow(); } while (previewAgain);
  } catch (e) {
    setStatus(e.message, true);
  } finally {
    previewBusy = false;
  }
}

async function refreshPreviewNow() {
  const v = state.version;
  if (state.kind === "workspace") {
    state.workspace = await api("GET", "/api/workspace");
    // Its patches' pictures are drawn with the load: wait for them rather than show the last load's.
    if (state.workspace.patches?.length) await drawn(`/api/preview/patch-0.png?v=${v}`, v);
    if (state.version !== v) return;
    drawWorkspace();
    return;
  }
  const [preview, field] = await Promise.all([
    drawn(`/api/preview/preview.json?v=${v}`, v).then((r) => r?.ok ? r.json() : null),
    drawn(`/api/preview/field.json?v=${v}`, v).then((r) => r?.ok ? r.json() : null),
  ]);
  if (state.version !== v) return;  // a newer load came meanwhile: refreshPreview asks again for it
  state.preview = preview;
  state.field = field;
  if (state.zoom) {
    await showZoomed(v);
  } else {
    await showPreviewWindow(v, preview);
  }
  const svg = await fetch(`/api/preview/scan.svg?v=${v}`).then((r) => r.ok ? r.text() : "");
  $("#scan").innerHTML = svg;
  $("#stage").dataset.version = v;
  drawOverlay();
}

// A preview file of load `v`: the studio answers 503 while that load is still being drawn (its files
// are then an older load's), and the page asks again until it is drawn or a newer load replaces it
// (then null).
async function drawn(url, v) {
  for (;;) {
    const r = await fetch(url);
    if (r.status !== 503) return r;
    if (state.version !== v) return null;
    await new Promise((done) => setTimeout(done, 250));
  }
}

// A window of the caller's choosing over the patch, drawn by the studio on request (/api/view).
async function showZoomed(v) {
  const z = state.zoom;
  fitStage();
  const q = `kind=${state.view === "field" ? "field" : "height"}&x_mm=${z.cx}&y_mm=${z.cy}&w_mm=${z.w}&h_mm=${z.h}`;
  const view = await api("GET", `/api/view?${q}`);
  const img = $("#picture");
  $("#stage").dataset.zoom = `${z.cx.toFixed(3)},${z.cy.toFixed(3)},${z.w.toFixed(3)},${z.h.toFixed(3)}`;
  if (!view.png) {
    img.hidden = true;
    $("#picture-caption").textContent = "No picture: no force depends on position alone." +
      (view.left_out?.length ? " " + view.left_out.join(" ") : "");
    return;
  }
  img.src = view.png;
  img.hidden = false;
  await img.decode().catch(() => {});
  img.style.transform = "";
  const whole = state.patchMm && z.w >= state.patchMm[0] - 1e-6 && z.h >= state.patchMm[1] - 1e-6;
  $("#picture-caption").textContent = `${view.window_mm[0].toFixed(1)} × ${view.window_mm[1].toFixed(1)} mm` +
    (whole ? " (the whole patch)" : ` around (${z.cx.toFixed(1)}, ${z.cy.toFixed(1)}) mm`) +
    ` · ${view.pixel_mm.toPrecision(3)} mm a pixel · ` +
    (state.view === "field" ? `force field at rest: hue = direction, brightness = |F| up to ${view.field_max_N.toFixed(3)} N`
                            : "height field, lit from the upper left") +
    (view.finer_than_pixel ? " · its finest detail (a grating's walls, a height map's samples) is under a pixel here: zoom in for it" : "") +
    (view.left_out?.length ? ` · not drawn: ${view.left_out.join("; ")}` : "") +
    ($("#arrows").checked ? " · arrows are drawn in the preview's own window only" : "") +
    " · wheel or +/− to zoom, Shift-drag to pan";
}

// The preview's window may be a part of the patch (as much as its pixels resolve): said, with the way to all of it.
function partOfPatch(w) {
  const p = state.patchMm;
  if (!p || (w[0] >= p[0] - 0.05 && w[1] >= p[1] - 0.05)) return "";
  return ` of the ${p[0].toFixed(1)} × ${p[1].toFixed(1)} mm patch (the part its pixels resolve; "whole patch" shows all of it)`;
}

// What the arrows stand for, in newtons (they are drawn in the preview's own window).
function arrowsCaption() {
  const f = state.field;
  if (!$("#arrows").checked || !f?.x_mm || !(f.max_N > 0)) return "";
  return ` · arrows: the strongest force at rest in each ${f.cell_mm[0].toPrecision(2)} mm cell, drawn from where it is;` +
    ` the longest is ${f.max_N.toPrecision(3)} N`;
}

// The latest call: a picture that decodes after a newer one was asked for must not write its caption.
let previewShown = 0;
async function showPreviewWindow(v, preview) {
  const mine = ++previewShown;
  delete $("#stage").dataset.zoom;
  $("#picture").style.transform = "";
  fitStage();
  const img = $("#picture");
  if (preview && preview.pixels) {
    img.src = `/api/preview/${state.view === "field" ? "field" : "height"}.png?v=${v}`;
    img.hidden = false;
    await img.decode().catch(() => {});
    if (mine !== previewShown) return;
    $("#picture-caption").textContent = `${preview.window_mm[0].toFixed(1)} × ${preview.window_mm[1].toFixed(1)} mm` +
      partOfPatch(preview.window_mm) + ` · scale bar ${preview.scale_bar_mm} mm · ` + (state.view === "field"
        ? `force field at rest: hue = direction, brightness = |F| up to ${preview.field_max_N.toFixed(3)} N` +
          (preview.field_limit_N > 0 && preview.field_max_N >= preview.field_limit_N * (1 - 1e-9)
            ? ` (the device's limit)` : "") +
          (preview.field_left_out?.length ? ` · not drawn: ${preview.field_left_out.join("; ")}` : "")
        : "height field, lit from the upper left" +
          (preview.left_out?.length ? ` · not drawn: ${preview.left_out.join("; ")}` : "")) +
      arrowsCaption();
  } else {
    img.hidden = true;
    $("#picture-caption").textContent = "No picture: no force depends on position alone." +
      (preview?.left_out?.length ? " " + preview.left_out.join(" ") : "");
  }
}
