// Sandpaper Studio's page (docs/STUDIO.md): the editor with the compiler's diagnostics, the preview of
// what plays, sliders for its numbers, Dummy mode (the mouse moves the simulated hand), the live servo
// figures, the workspace canvas, and a scene's 3-D view (scene.js). Everything it knows comes from the studio's JSON API.
// This file wires the page's modules together and starts it.
import { api } from "./api.js";
import { applyCompile, compileNow, flushCompile } from "./compile.js";
import { editor } from "./editor.js";
import { anyUnsaved, refreshFileList } from "./file-list.js";
import { loadCurrent, newOrSaveAs, open, save } from "./files.js";
import { hooks } from "./hooks.js";
import { setupLibrary } from "./library.js";
import { connectEvents } from "./live.js";
import { drawOverlay } from "./overlay.js";
import { $, setStatus } from "./page.js";
import { setupStage } from "./pointer.js";
import { refreshPreview } from "./preview.js";
import { setupScene } from "./scene.js";
import { state } from "./state.js";
import { drawWorkspace } from "./workspace.js";
import { setupZoom } from "./zoom.js";

// Before anything can type, save or answer: the modules below compile.js call these through hooks.
Object.assign(hooks, { compileNow, flushCompile, save, applyCompile });

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
  setupLibrary();
  document.querySelectorAll("input[name=view]").forEach((r) => r.addEventListener("change", () => { state.view = r.value; refreshPreview(); }));
  document.querySelectorAll("input[name=mode]").forEach((r) => r.addEventListener("change", () => { state.mode = r.value; drawWorkspace(); }));
  $("#arrows").addEventListener("change", () => refreshPreview());  // the caption says what the arrows stand for
  setupStage();
  setupZoom();
  setupScene();
  // Started on a folder, nothing plays until a file is chosen.
  const cur = await api("GET", "/api/current");
  if (cur.file) {
    await loadCurrent();
    await refreshFileList();
  } else {
    setStatus("choose a file to play from the list");
  }
  connectEvents();
  // A scene's view follows its pane's size by itself (scene3d/view.js).
  window.addEventListener("resize", () => (state.kind === "workspace" ? drawWorkspace() : state.kind === "material" && drawOverlay()));
  document.body.dataset.ready = "yes";
}

// For tests and scripts driving the page: the editor's text, without reaching into CodeMirror.
// settled(): once what was typed has reached the studio and its answer has come back.
window.studio = { text: () => editor.state.doc.toString(), state, editor,
                  settled: async () => { await flushCompile(); await state.compiling; return true; } };
init().catch((e) => setStatus(e.message, true));
