// Opening, saving, creating files: each open file's editor state kept while another is open.
import { EditorState } from "@codemirror/state";
import { api } from "./api.js";
import { applyCompile, flushCompile } from "./compile.js";
import { editor, editorExtensions, setText } from "./editor.js";
import { markUnsaved, refreshFileList } from "./file-list.js";
import { $, setStatus } from "./page.js";
import { state } from "./state.js";

// Each file's editor state (its text, selection and undo history) while another file is open, so
// that undo never reaches across files and a file comes back as it was left.
const fileStates = new Map();

export async function open(file) {
  // Whatever was typed reaches the studio as the file it was typed in, before the file changes.
  await flushCompile();
  await state.compiling;
  state.opening = true;
  state.zoom = null;  // a new patch: its own preview window first
  state.patchMm = null;
  try {
    var r = await api("POST", "/api/open", { file });
    var cur = await loadCurrent();
    if ($("#file").options[0]?.value === "") await refreshFileList();  // the "choose a file" entry goes
  } finally {
    state.opening = false;
  }
  // Every open says which file it opened: a word about the file left must not stay beside this one.
  // A recovery copy's offer (loadCurrent) is that word.
  if (!cur.recovered) setStatus(r.restored_unsaved ? `${file}: your unsaved edits, as you left them` : `opened ${file}`);
  return r;
}

export async function loadCurrent() {
  const editsAsked = state.edits;
  const cur = await api("GET", "/api/current");
  // Two loads can overlap (an open, and the state events following a change made elsewhere): one
  // answered after an edit typed in this file is older than the edit, and would drop it.
  if (state.file === cur.file && state.edits !== editsAsked) return cur;
  if (state.file && state.file !== cur.file) fileStates.set(state.file, editor.state);
  const kept = fileStates.get(cur.file);
  fileStates.delete(cur.file);
  if (state.file !== cur.file) {
    state.remote = true;
    // A recovery copy's text starts from the file's, so that undo goes back to what is on disk.
    const start = cur.recovered ? cur.recovered.saved_text : cur.text;
    editor.setState(kept && kept.doc.toString() === cur.text ? kept : EditorState.create({ doc: start, extensions: editorExtensions }));
    state.remote = false;
  }
  state.file = cur.file;
  state.kind = cur.kind;
  document.body.dataset.kind = cur.kind;
  $("#file").value = cur.file;
  setText(cur.text);
  state.textVersion = cur.text_version;
  applyCompile({ ...cur.compile, parameters: cur.parameters, version: cur.version, saved: cur.saved });
  if (cur.recovered)
    setStatus(`${cur.file}: the unsaved edits a stopped studio kept in ${cur.recovered.copy}; Ctrl-S saves them, Ctrl-Z goes back to the file`);
  return cur;
}

export async function save() {
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

// New file and Save as: the name typed beside the buttons, inside the studio's folder.
export async function newOrSaveAs(path, verb) {
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
