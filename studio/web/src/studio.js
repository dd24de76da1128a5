// Sandpaper Studio's page (docs/STUDIO.md): the editor with the compiler's diagnostics, the preview of
// what plays, sliders for its numbers, Dummy mode (the mouse moves the simulated hand), the live servo
// figures, and the workspace canvas. Everything it knows comes from the studio's JSON API.
import { EditorView, basicSetup } from "codemirror";
import { hoverTooltip } from "@codemirror/view";
import { EditorState } from "@codemirror/state";
import { setDiagnostics, lintGutter } from "@codemirror/lint";
import { hmatLanguage } from "./hmat.js";

const $ = (sel) => document.querySelector(sel);
const state = {
  file: "", kind: "material", version: 0, parameters: [], preview: null, field: null, workspace: null,
  live: null, strip: [], selected: -1, mode: "normal", view: "height", remote: false, compileTimer: 0,
  lastCompileMs: 0,
  zoom: null,       // null: the preview's own window; else {cx, cy, w, h}, mm, a window over the patch
  patchMm: null,    // the playing material's patch [width, height], mm
};

async function api(method, path, body, json = true) {
  const init = { method, headers: {} };
  if (body !== undefined) {
    init.body = json ? JSON.stringify(body) : body;
    init.headers["Content-Type"] = json ? "application/json" : "text/plain; charset=utf-8";
  }
  const res = await fetch(path, init);
  const data = await res.json().catch(() => ({}));
  if (!res.ok) throw new Error(data.error || `${method} ${path}: HTTP ${res.status}`);
  return data;
}

// A roughness as every Sandpaper output prints it: three significant digits (schema::roughness_text).
function roughnessText(r) { return String(Number(r.toPrecision(3))); }

function setStatus(text, bad = false) {
  const s = $("#status");
  s.textContent = text;
  s.title = text;  // the whole of it, when the header's one line cuts it short
  s.classList.toggle("bad", bad);
}

// ---- editor ------------------------------------------------------------------------------------
// What `sandpaper lsp` gives an editor, asked of the studio (POST /api/language), which answers with
// the language server's own code for the text it holds: so first the typed text reaches it.
async function language(feature, doc, pos) {
  await flushCompile();
  await state.compiling;
  const line = doc.lineAt(pos);
  return api("POST", "/api/language", { feature, line: line.number - 1, character: pos - line.from });
}

const completionTypes = { 14: "keyword", 12: "constant", 11: "unit", 9: "namespace" };
// Completion: statement keywords, library names after `like` (with what each describes), levels
// after `roughness`, units after a number. The server gives every candidate for the place; the
// editor filters them by what is typed.
async function lspCompletion(context) {
  const word = context.matchBefore(/[A-Za-z0-9_\-\/%*.]*/);
  if (!context.explicit && word.from === word.to && !/[ \t]$/.test(context.state.sliceDoc(Math.max(0, context.pos - 1), context.pos)))
    return null;
  let items;
  try {
    items = await language("completion", context.state.doc, context.pos);
  } catch {
    return null;
  }
  if (context.aborted || !Array.isArray(items) || !items.length) return null;
  return {
    from: word.from,
    options: items.map((i) => ({ label: i.label, detail: i.detail, type: completionTypes[i.kind] || "variable",
                                 info: i.documentation?.value || i.documentation })),
    validFor: /^[A-Za-z0-9_\-\/%*.]*$/,
  };
}

// Hover: explain's line for a number (parameter, value, layer, source), or a `like` name's entry.
const lspHover = hoverTooltip(async (view, pos) => {
  let r;
  try {
    r = await language("hover", view.state.doc, pos);
  } catch {
    return null;
  }
  const value = r?.contents?.value ?? (typeof r?.contents === "string" ? r.contents : "");
  if (!value) return null;
  return {
    pos,
    above: true,
    create() {
      const dom = document.createElement("pre");
      dom.className = "hover";
      dom.textContent = value.replace(/^```text\n/, "").replace(/\n?```\s*$/, "");
      return { dom };
    },
  };
});

// Go to definition (F12): the library entry a `like` names, said in the status line.
async function goToDefinition(view) {
  const r = await language("definition", view.state.doc, view.state.selection.main.head).catch(() => null);
  if (!r || !r.uri) { setStatus("no definition here: F12 on a library name after `like`"); return; }
  const file = decodeURIComponent(r.uri.replace(/^file:\/\//, ""));
  setStatus(`defined in ${file}, line ${r.range.start.line + 1}`);
  document.body.dataset.definition = file;
}

const editorExtensions = [
  basicSetup, hmatLanguage, lintGutter(),
  EditorView.updateListener.of((u) => {
    if (!u.docChanged || state.remote) return;
    clearTimeout(state.compileTimer);
    // Short enough that diagnostics follow typing within 150 ms, long enough to skip keystrokes
    // typed in one burst.
    state.compileTimer = setTimeout(compileNow, 30);
  }),
  EditorView.domEventHandlers({
    keydown: (e, view) => {
      if ((e.ctrlKey || e.metaKey) && e.key === "s") { e.preventDefault(); save(); return true; }
      if (e.key === "F12") { e.preventDefault(); goToDefinition(view); return true; }
      return false;
    },
  }),
  EditorState.languageData.of(() => [{ autocomplete: lspCompletion }]),
  lspHover,
];
const editor = new EditorView({ parent: $("#editor"), state: EditorState.create({ doc: "", extensions: editorExtensions }) });
// Each file's editor state (its text, selection and undo history) while another file is open, so
// that undo never reaches across files and a file comes back as it was left.
const fileStates = new Map();

// The studio's text into the editor (it is the studio's, so it is not sent back).
function setText(text) {
  state.sentText = text;
  const old = editor.state.doc.toString();
  if (old === text) return;
  // One change over the differing middle, so the cursor and the undo history keep their places.
  let a = 0;
  while (a < old.length && a < text.length && old[a] === text[a]) a++;
  let b = 0;
  while (b < old.length - a && b < text.length - a && old[old.length - 1 - b] === text[text.length - 1 - b]) b++;
  state.remote = true;
  editor.dispatch({ changes: { from: a, to: old.length - b, insert: text.slice(a, text.length - b) } });
  state.remote = false;
}

function toEditorDiagnostics(list) {
  const doc = editor.state.doc;
  const out = [];
  for (const d of list) {
    if (!d.line || d.line > doc.lines) continue;
    const line = doc.line(d.line);
    const from = Math.min(line.from + Math.max(0, d.column - 1), line.to);
    let to = from;
    while (to < line.to && !/\s/.test(doc.sliceString(to, to + 1))) to++;
    if (to === from) to = Math.min(from + 1, doc.length);
    out.push({ from, to, severity: d.severity === "error" ? "error" : "warning",
               message: `${d.code}: ${d.message}` + (d.suggestion ? `\nhelp: ${d.suggestion}` : "") });
  }
  return out;
}

function showDiagnostics(list) {
  editor.dispatch(setDiagnostics(editor.state, toEditorDiagnostics(list)));
  const ul = $("#diagnostics");
  ul.replaceChildren();
  for (const d of list) {
    const li = document.createElement("li");
    li.className = d.severity;
    li.dataset.line = d.line;
    li.dataset.column = d.column;
    li.dataset.code = d.code;
    li.innerHTML = `<b>${d.line}:${d.column}</b> <span class="code">${d.code}</span> `;
    li.append(document.createTextNode(d.message));
    if (d.suggestion) {
      const help = document.createElement("div");
      help.className = "help";
      help.textContent = "help: " + d.suggestion;
      li.append(help);
    }
    li.addEventListener("click", () => {
      const line = editor.state.doc.line(Math.min(d.line, editor.state.doc.lines));
      editor.dispatch({ selection: { anchor: line.from + Math.max(0, d.column - 1) }, scrollIntoView: true });
      editor.focus();
    });
    ul.append(li);
  }
  $("#diagnostics-title").textContent = list.length ? `Diagnostics (${list.length})` : "No diagnostics";
}

function compileNow() {
  state.compileTimer = 0;
  const text = editor.state.doc.toString();
  const t0 = performance.now();
  // Remembered, so that opening another file waits for it: posted after the open, it would become
  // the other file's text.
  state.sentText = text;
  const sent = (async () => {
    try {
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

function applyCompile(r) {
  showDiagnostics(r.diagnostics || []);
  document.body.dataset.compiles = r.ok ? "yes" : "no";
  $("#stale").textContent = r.version
    ? `the last good picture (v${r.version}, still playing): this text does not compile`
    : "nothing has compiled yet: this text does not compile";
  $("#compile-state").title = $("#compile-state").textContent = r.ok
    ? `compiled: ${r.material || r.workspace?.name || ""}` +
      (r.compiled_max_lateral_force_N !== undefined ? ` · ${r.compiled_max_lateral_force_N.toFixed(3)} N, roughness ${roughnessText(r.compiled_roughness)}` : "")
    : "does not compile: the last good program keeps playing";
  $("#saved").textContent = r.saved ? "saved" : "unsaved";
  markUnsaved(state.file, !r.saved);
  state.version = r.version;
  if (r.ok && r.size_m) state.patchMm = [r.size_m[0] * 1e3, r.size_m[1] * 1e3];
  if (r.text_version !== undefined) state.textVersion = Math.max(state.textVersion || 0, r.text_version);
  renderSliders(r.parameters || []);
  if (r.ok) refreshPreview();
}

// ---- sliders -----------------------------------------------------------------------------------
function renderSliders(params) {
  const box = $("#sliders");
  const same = params.length === state.parameters.length && params.every((p, i) => p.name === state.parameters[i].name);
  state.parameters = params;
  if (!same) {
    box.replaceChildren();
    for (const p of params) {
      const row = document.createElement("label");
      row.className = "slider " + p.layer;
      row.innerHTML = `<span class="name"></span><input type="range"><output></output>`;
      row.querySelector(".name").textContent = p.label;
      const input = row.querySelector("input");
      input.dataset.name = p.name;
      input.addEventListener("input", () => sliderMoved(input));
      box.append(row);
    }
    if (!params.length) box.textContent = "No numbers to tune in this text.";
  }
  box.querySelectorAll("input[type=range]").forEach((input, i) => {
    const p = params[i];
    if (sliderSends.get(p.name)?.busy) return;  // the hand is on it: leave it where the hand put it
    input.min = p.min; input.max = p.max; input.step = p.step; input.value = p.value;
    input.dataset.unit = p.unit;
    input.nextElementSibling.textContent = `${p.value} ${p.unit}`.trim();
  });
}

// While a slider moves, its value goes to the studio at once when no request is in flight, else as
// soon as the one in flight returns (only the latest value): the material follows the hand on the
// slider, and the last value arrives one round trip after the last move.
const sliderSends = new Map();
function sliderMoved(input) {
  const name = input.dataset.name;
  const step = input.step.includes(".") ? input.step.split(".")[1].length : 0;
  const value = Number(Number(input.value).toFixed(step));
  input.nextElementSibling.textContent = `${value} ${input.dataset.unit}`.trim();
  const s = sliderSends.get(name) || { busy: false, next: null };
  sliderSends.set(name, s);
  s.next = value;
  if (!s.busy) sendSlider(name, input.dataset.unit, s);
}

async function sendSlider(name, unit, s) {
  s.busy = true;
  document.body.dataset.sliderBusy = "yes";
  while (s.next !== null) {
    const value = s.next;
    s.next = null;
    try {
      const r = await api("POST", "/api/parameter", { name, value, unit });
      setText(r.text);
      applyCompile(r, true);
    } catch (e) {
      setStatus(e.message, true);
    }
  }
  s.busy = false;
  if (![...sliderSends.values()].some((x) => x.busy)) document.body.dataset.sliderBusy = "no";
}

// ---- preview -----------------------------------------------------------------------------------
// One refresh at a time, the latest version last: a browser has six connections to the studio, and
// pictures waiting for their render must not hold them all while a slider's edits queue behind them.
let previewBusy = false, previewAgain = false;
async function refreshPreview() {
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
    drawWorkspace();
    return;
  }
  const [preview, field] = await Promise.all([
    fetch(`/api/preview/preview.json?v=${v}`).then((r) => r.ok ? r.json() : null),
    fetch(`/api/preview/field.json?v=${v}`).then((r) => r.ok ? r.json() : null),
  ]);
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

async function showPreviewWindow(v, preview) {
  delete $("#stage").dataset.zoom;
  $("#picture").style.transform = "";
  fitStage();
  const img = $("#picture");
  if (preview && preview.pixels) {
    img.src = `/api/preview/${state.view === "field" ? "field" : "height"}.png?v=${v}`;
    img.hidden = false;
    await img.decode().catch(() => {});
    $("#picture-caption").textContent = `${preview.window_mm[0].toFixed(1)} × ${preview.window_mm[1].toFixed(1)} mm` +
      ` · scale bar ${preview.scale_bar_mm} mm · ` + (state.view === "field"
        ? `force field at rest: hue = direction, brightness = |F| up to ${preview.field_max_N.toFixed(3)} N` +
          (preview.field_limit_N > 0 && preview.field_max_N >= preview.field_limit_N * (1 - 1e-9)
            ? ` (the device's limit)` : "") +
          (preview.field_left_out?.length ? ` · not drawn: ${preview.field_left_out.join("; ")}` : "")
        : "height field, lit from the upper left" +
          (preview.left_out?.length ? ` · not drawn: ${preview.left_out.join("; ")}` : ""));
  } else {
    img.hidden = true;
    $("#picture-caption").textContent = "No picture: no force depends on position alone." +
      (preview?.left_out?.length ? " " + preview.left_out.join(" ") : "");
  }
}

// Stage pixels <-> millimetres: the picture covers window_mm centred on the patch centre (material),
// or on the zoom's centre, or the workspace's rectangle (workspace); y up.
function windowMm() {
  if (state.kind === "workspace") return state.workspace?.size_mm || [228.6, 228.6];
  if (state.zoom) return [state.zoom.w, state.zoom.h];
  return state.preview?.window_mm || [80, 80];
}
function centreMm() {
  return state.kind === "material" && state.zoom ? [state.zoom.cx, state.zoom.cy] : [0, 0];
}
// The stage takes the shape of what it shows, so that a picture is never stretched (a 60 x 39.8 mm
// photograph is drawn 3:2, not square) and pixels map to millimetres alike across and down.
function fitStage() {
  const [w, h] = windowMm();
  if (w > 0 && h > 0) $("#stage").style.aspectRatio = `${w} / ${h}`;
}
function toMm(ev) {
  const r = $("#stage").getBoundingClientRect();
  const [w, h] = windowMm(), [cx, cy] = centreMm();
  return [cx + ((ev.clientX - r.left) / r.width - 0.5) * w, cy + (0.5 - (ev.clientY - r.top) / r.height) * h];
}
function toPx(xMm, yMm, r) {
  const [w, h] = windowMm(), [cx, cy] = centreMm();
  return [((xMm - cx) / w + 0.5) * r.width, (0.5 - (yMm - cy) / h) * r.height];
}

// ---- zoom and pan over the whole patch ---------------------------------------------------------
// A window of the patch kept inside it (a window larger than the patch is centred), at least 0.05 mm.
function clampZoom(z) {
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
function currentWindow() {
  const [w, h] = windowMm(), [cx, cy] = centreMm();
  return { cx, cy, w, h };
}
// Zooms by `factor` (> 1: in) keeping the place under (xMm, yMm) where it is on the stage.
function zoomAbout(factor, xMm, yMm) {
  const z = currentWindow();
  const w = z.w / factor, h = z.h / factor;
  setZoom({ cx: xMm - (xMm - z.cx) / factor, cy: yMm - (yMm - z.cy) / factor, w, h });
}
function setupZoom() {
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

function drawOverlay() {
  const canvas = $("#overlay");
  const stage = $("#stage");
  const r = stage.getBoundingClientRect();
  if (canvas.width !== Math.round(r.width) || canvas.height !== Math.round(r.height)) {
    canvas.width = Math.round(r.width);
    canvas.height = Math.round(r.height);
  }
  const g = canvas.getContext("2d");
  g.clearRect(0, 0, canvas.width, canvas.height);
  // Field arrows (materials): where and which way a slow hand is pushed.
  const f = state.field;
  if (state.kind === "material" && !state.zoom && f && f.n && f.max_N > 0 && $("#arrows").checked) {
    g.strokeStyle = "rgba(30, 90, 200, 0.7)";
    g.lineWidth = 1;
    const cell = canvas.width / f.n;
    for (let row = 0; row < f.n; row++) for (let col = 0; col < f.n; col++) {
      const i = row * f.n + col;
      const fx = f.fx_N[i] / f.max_N, fy = f.fy_N[i] / f.max_N;
      const cx = (col + 0.5) * cell, cy = (row + 0.5) * (canvas.height / f.n);
      arrow(g, cx, cy, cx + fx * cell * 0.45, cy - fy * cell * 0.45, 3);
    }
  }
  const live = state.live;
  if (!live) return;
  const [hx, hy] = toPx(live.hand[0], live.hand[1], r);
  const scale = 80 / Math.max(live.compiled_max_lateral_force_N || 1, 0.05);  // the compiled maximum is 80 px
  const fx = live.force_N[0] * scale, fy = live.force_N[1] * scale;
  g.beginPath();
  g.arc(hx, hy, 7, 0, 2 * Math.PI);
  g.lineWidth = 2;
  g.strokeStyle = "#111";
  g.fillStyle = "rgba(255, 210, 60, 0.9)";
  g.fill();
  g.stroke();
  // The force on the hand, from its centre, drawn over it.
  g.strokeStyle = "#c0392b";
  g.fillStyle = "#c0392b";
  g.lineWidth = 3;
  arrow(g, hx, hy, hx + fx, hy - fy, 9);
  stage.dataset.hand = `${live.hand[0].toFixed(3)},${live.hand[1].toFixed(3)}`;
  stage.dataset.force = `${live.force_N[0].toFixed(4)},${live.force_N[1].toFixed(4)}`;
  stage.dataset.handPx = `${hx.toFixed(1)},${hy.toFixed(1)}`;
  stage.dataset.arrowPx = `${(hx + fx).toFixed(1)},${(hy - fy).toFixed(1)}`;
}

function arrow(g, x0, y0, x1, y1, head) {
  g.beginPath();
  g.moveTo(x0, y0);
  g.lineTo(x1, y1);
  g.stroke();
  const len = Math.hypot(x1 - x0, y1 - y0);
  if (len < 2) return;
  const ux = (x1 - x0) / len, uy = (y1 - y0) / len;
  g.beginPath();
  g.moveTo(x1, y1);
  g.lineTo(x1 - head * ux + head * 0.5 * uy, y1 - head * uy - head * 0.5 * ux);
  g.lineTo(x1 - head * ux - head * 0.5 * uy, y1 - head * uy + head * 0.5 * ux);
  g.closePath();
  g.fill();
}

// ---- Dummy mode: the mouse moves the simulated hand ----------------------------------------------
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

function setupStage() {
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

// ---- workspace canvas ----------------------------------------------------------------------------
let wsDrag = null;
function drawWorkspace() {
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

function workspacePointerDown(ev) {
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
function workspacePointerMove(ev) {
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
async function workspacePointerUp() {
  if (!wsDrag) return false;
  const p = state.workspace.patches[wsDrag.i];
  const round = (v) => Math.round(v * 10) / 10;
  wsDrag = null;
  try {
    const r = await api("POST", "/api/workspace/patch", { index: p.index, x_mm: round(p.centre_mm[0]), y_mm: round(p.centre_mm[1]),
      width_mm: round(p.size_mm[0]), height_mm: round(p.size_mm[1]) });
    setText(r.text);
    applyCompile(r);
  } catch (e) {
    setStatus(e.message, true);
  }
  return true;
}

// ---- live figures ------------------------------------------------------------------------------
// The studio owns the text: a change made elsewhere (the HTTP API, another tab) arrives with the
// state events as a higher text_version, and the page takes the studio's text and figures, unless
// its own edit is on its way (then that edit's answer brings them).
let following = false;
async function followDocument(d) {
  if (!d || following || !d.file) return;
  const behind = d.file !== state.file || d.text_version > (state.textVersion || 0);
  if (!state.file && behind) {  // a file opened elsewhere (another tab, the API) while none was open here
    following = true;
    try { await loadCurrent(); await refreshFileList(); } finally { following = false; }
    return;
  }
  if (!behind || state.compileTimer || state.opening || document.body.dataset.sliderBusy === "yes") return;
  following = true;
  try {
    await state.compiling;
    const cur = await api("GET", "/api/current");
    if (state.compileTimer || editor.state.doc.toString() !== state.sentText && cur.file === state.file) return;
    if (cur.file !== state.file) {
      await loadCurrent();
    } else {
      setText(cur.text);
      applyCompile({ ...cur.compile, parameters: cur.parameters, version: cur.version, saved: cur.saved,
                     text_version: cur.text_version });
    }
  } catch (e) {
    setStatus(e.message, true);
  } finally {
    following = false;
  }
}

function onState(s) {
  state.live = s;
  followDocument(s.document);
  // Which program plays, beside the text: a text that does not compile leaves an older one playing.
  const d = s.document;
  document.body.dataset.playingVersion = s.material_version;
  $("#playing-what").textContent = d && s.material_version
    ? (d.compiles && d.version === s.material_version ? `playing this text (v${s.material_version})`
                                                      : `playing v${s.material_version}, an earlier text`)
    : "";
  $("#rate").textContent = s.rate_hz.toFixed(1);
  $("#ticks").textContent = s.ticks;
  $("#overruns").textContent = s.overruns;
  $("#force").textContent = Math.hypot(s.force_N[0], s.force_N[1]).toFixed(3);
  $("#felt").textContent = s.felt_max_lateral_force_N.toFixed(3);
  $("#playing").textContent = s.material ? `${s.material} (v${s.material_version})` : "nothing yet";
  $("#servo").textContent = s.running ? "running" : `stopped: ${s.stop_cause}`;
  state.strip.push(Math.hypot(s.force_N[0], s.force_N[1]));
  if (state.strip.length > 300) state.strip.shift();
  drawStrip();
  if (state.kind === "material") drawOverlay();
  else drawWorkspaceHand();
}

function drawWorkspaceHand() {
  drawOverlay();
}

function drawStrip() {
  const c = $("#strip");
  const g = c.getContext("2d");
  g.clearRect(0, 0, c.width, c.height);
  const top = Math.max(0.05, ...state.strip, state.live?.compiled_max_lateral_force_N || 0);
  g.strokeStyle = "#8a4b08";
  g.lineWidth = 1.5;
  g.beginPath();
  state.strip.forEach((v, i) => {
    const x = (i / 299) * c.width, y = c.height - 4 - (v / top) * (c.height - 8);
    if (i) g.lineTo(x, y); else g.moveTo(x, y);
  });
  g.stroke();
  $("#strip-scale").textContent = `|F|, last 10 s, 0 to ${top.toFixed(2)} N`;
}

function connectEvents() {
  const es = new EventSource("/api/events");
  es.onmessage = (e) => onState(JSON.parse(e.data));
  es.onerror = () => setStatus("lost the studio's event stream; retrying", true);
  es.onopen = () => setStatus("connected");
}

// ---- library browser ----------------------------------------------------------------------------
// Search the library (its SQLite index, as `sandpaper library search`), see an entry's numbers and
// picture, insert `like NAME` into the text, or read the entry's file (read-only: it is the library's).
let librarySearchTimer = 0;
async function searchLibrary() {
  const q = $("#library-search").value.trim();
  const ul = $("#library-results");
  try {
    const r = await api("GET", `/api/library/search?q=${encodeURIComponent(q)}`);
    if ($("#library-search").value.trim() !== q) return;  // typed on meanwhile
    ul.replaceChildren();
    for (const e of r.entries) {
      const li = document.createElement("li");
      li.dataset.name = e.name;
      li.innerHTML = `<span class="name"></span><span class="figures"></span><span class="describes"></span>`;
      li.querySelector(".name").textContent = e.name;
      li.querySelector(".figures").textContent = e.compiled_max_lateral_force_N > 0
        ? `roughness ${roughnessText(e.compiled_roughness)}, ${e.compiled_max_lateral_force_N.toFixed(2)} N` : "untextured";
      li.querySelector(".describes").textContent = e.describes;
      li.addEventListener("click", () => showLibraryEntry(e.name));
      ul.append(li);
    }
    if (!r.entries.length) ul.textContent = "nothing in the library matches";
  } catch (e) {
    setStatus(e.message, true);
  }
}

async function showLibraryEntry(name) {
  const e = await api("GET", `/api/library/entry?name=${encodeURIComponent(name)}`).catch((x) => { setStatus(x.message, true); });
  if (!e) return;
  document.querySelectorAll("#library-results li").forEach((li) => li.classList.toggle("selected", li.dataset.name === e.name));
  $("#library-entry").hidden = false;
  $("#library-entry").dataset.name = e.name;
  const img = $("#library-picture");
  img.hidden = !e.picture;
  if (e.picture) img.src = `/api/library/picture?name=${encodeURIComponent(e.name)}`;
  const figures = e.compiled_max_lateral_force_N > 0
    ? `compiled roughness ${roughnessText(e.compiled_roughness)}, maximum lateral force ${e.compiled_max_lateral_force_N.toFixed(3)} N` +
      (e.period_mm ? `, period ${e.period_mm.toFixed(2)} mm` : "")
    : "no texture";
  $("#library-numbers").textContent = `${e.name} (${e.family}): ${e.describes}. ${figures}. ${e.file}`;
  $("#library-insert").textContent = `insert like ${e.name}`;
  $("#library-text").textContent = e.text;
  $("#library-text").hidden = true;
}

function insertLike() {
  const name = $("#library-entry").dataset.name;
  if (!name) return;
  const line = editor.state.doc.lineAt(editor.state.selection.main.head);
  const text = `\n  like ${name}`;
  editor.dispatch({ changes: { from: line.to, insert: text }, selection: { anchor: line.to + text.length }, scrollIntoView: true });
  editor.focus();
}

// ---- files, saving -------------------------------------------------------------------------------
// The file list marks files whose edits are not saved (the studio keeps them while another file is
// open: GET /api/files "unsaved").
function markUnsaved(file, unsaved) {
  for (const o of $("#file").options) {
    if (o.value !== file || !file) continue;
    o.textContent = unsaved ? `${file} \u25CF` : file;
    o.dataset.unsaved = unsaved ? "yes" : "no";
  }
}

function anyUnsaved() {
  return [...$("#file").options].some((o) => o.dataset.unsaved === "yes");
}

async function open(file) {
  // Whatever was typed reaches the studio as the file it was typed in, before the file changes.
  await flushCompile();
  await state.compiling;
  state.opening = true;
  state.zoom = null;  // a new patch: its own preview window first
  state.patchMm = null;
  try {
    var r = await api("POST", "/api/open", { file });
    await loadCurrent();
    if ($("#file").options[0]?.value === "") await refreshFileList();  // the "choose a file" entry goes
  } finally {
    state.opening = false;
  }
  if (r.restored_unsaved) setStatus(`${file}: your unsaved edits, as you left them`);
  return r;
}

async function loadCurrent() {
  const cur = await api("GET", "/api/current");
  if (state.file && state.file !== cur.file) fileStates.set(state.file, editor.state);
  const kept = fileStates.get(cur.file);
  fileStates.delete(cur.file);
  if (state.file !== cur.file) {
    state.remote = true;
    editor.setState(kept && kept.doc.toString() === cur.text ? kept : EditorState.create({ doc: cur.text, extensions: editorExtensions }));
    state.remote = false;
  }
  state.file = cur.file;
  state.kind = cur.kind;
  document.body.dataset.kind = cur.kind;
  $("#file").value = cur.file;
  setText(cur.text);
  state.textVersion = cur.text_version;
  applyCompile({ ...cur.compile, parameters: cur.parameters, version: cur.version, saved: cur.saved });
}

async function save() {
  try {
    await flushCompile();
    const r = await api("POST", "/api/save");
    $("#saved").textContent = "saved";
    markUnsaved(r.file, false);
    setStatus(`saved ${r.file} (${r.bytes} bytes)`);
  } catch (e) {
    setStatus(e.message, true);
  }
}

async function flushCompile() {
  if (state.compileTimer) { clearTimeout(state.compileTimer); await compileNow(); }
}

// The folder's files into the list, the open one selected; none open: a first entry asks for one.
async function refreshFileList() {
  const { files, not_listed: notListed = [], unsaved = [] } = await api("GET", "/api/files");
  const sel = $("#file");
  sel.replaceChildren();
  if (!state.file) {
    const o = new Option("choose a file to play", "");
    o.disabled = true;
    sel.append(o);
  }
  for (const f of files) sel.append(new Option(f, f));
  // Names that are not UTF-8 cannot be asked for: shown, greyed, with what to do.
  for (const { file, why } of notListed) {
    const o = new Option(`${file} (${why})`, "");
    o.disabled = true;
    o.title = why;
    sel.append(o);
  }
  for (const f of unsaved) markUnsaved(f, true);
  sel.value = state.file || "";
  return files;
}

// New file and Save as: the name typed beside the buttons, inside the studio's folder.
async function newOrSaveAs(path, verb) {
  const file = $("#file-name").value.trim();
  if (!file) { setStatus("type the file's name first, e.g. silk.hmat or workspace/desk.hws", true); return; }
  await flushCompile();
  await state.compiling;
  state.opening = true;
  try {
    await api("POST", path, { file });
    await loadCurrent();
    await refreshFileList();
    $("#file-name").value = "";
    setStatus(`${verb} ${state.file}`);
  } catch (e) {
    setStatus(e.message, true);
  } finally {
    state.opening = false;
  }
}

async function init() {
  const sel = $("#file");
  await refreshFileList();
  sel.addEventListener("change", () => open(sel.value).catch((e) => setStatus(e.message, true)));
  // Closing or reloading the page with edits unsaved asks first (the browser's own question).
  window.addEventListener("beforeunload", (e) => {
    if (!anyUnsaved()) return;
    e.preventDefault();
    e.returnValue = "";
  });
  $("#save").addEventListener("click", save);
  $("#new").addEventListener("click", () => newOrSaveAs("/api/new", "created"));
  $("#save-as").addEventListener("click", () => newOrSaveAs("/api/save-as", "saved as"));
  $("#library-search").addEventListener("input", () => { clearTimeout(librarySearchTimer); librarySearchTimer = setTimeout(searchLibrary, 150); });
  $("#library-insert").addEventListener("click", insertLike);
  $("#library-read").addEventListener("click", () => { $("#library-text").hidden = !$("#library-text").hidden; });
  document.querySelectorAll("input[name=view]").forEach((r) => r.addEventListener("change", () => { state.view = r.value; refreshPreview(); }));
  document.querySelectorAll("input[name=mode]").forEach((r) => r.addEventListener("change", () => { state.mode = r.value; drawWorkspace(); }));
  $("#arrows").addEventListener("change", () => (state.zoom ? refreshPreview() : drawOverlay()));
  setupStage();
  setupZoom();
  // Started on a folder, nothing plays until a file is chosen.
  const cur = await api("GET", "/api/current");
  if (cur.file) {
    await loadCurrent();
    await refreshFileList();
  } else {
    setStatus("choose a file to play from the list");
  }
  connectEvents();
  window.addEventListener("resize", () => (state.kind === "workspace" ? drawWorkspace() : drawOverlay()));
  document.body.dataset.ready = "yes";
}

// For tests and scripts driving the page: the editor's text, without reaching into CodeMirror.
// settled(): once what was typed has reached the studio and its answer has come back.
window.studio = { text: () => editor.state.doc.toString(), state, editor,
                  settled: async () => { await flushCompile(); await state.compiling; return true; } };
init().catch((e) => setStatus(e.message, true));
