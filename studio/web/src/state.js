// The page's state, shared by every module (and shown to tests and scripts as window.studio.state):
// one object, so that each module reads what another wrote without importing it.
export const state = {
  file: "", kind: "material", version: 0, parameters: [], preview: null, field: null, workspace: null,
  live: null, strip: [], selected: -1, mode: "normal", view: "height", remote: false, compileTimer: 0,
  lastCompileMs: 0,
  edits: 0,         // edits typed here (not the studio's text set in): a fetch asked before one is older than it
  languageAsked: 0, // questions to the language server (completion, hover, F12) not yet answered
  zoom: null,       // null: the preview's own window; else {cx, cy, w, h}, mm, a window over the patch
  patchMm: null,    // the playing material's patch [width, height], mm
  sceneVersion: 0,  // the open scene's last good compile (GET /api/current "scene_version"); 0 none
  sceneTouch: null, // the 3-D Dummy mode's last answer (POST /api/scene/device)
};
