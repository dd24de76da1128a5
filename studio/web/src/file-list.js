// The file list (#file): the folder's files, the open one selected; apart from opening and saving so
// that compiling can mark a file unsaved without importing what compiles.
import { api } from "./api.js";
import { $ } from "./page.js";
import { state } from "./state.js";

// The file list marks files whose edits are not saved (the studio keeps them while another file is
// open: GET /api/files "unsaved").
export function markUnsaved(file, unsaved) {
  for (const o of $("#file").options) {
    if (o.value !== file || !file) continue;
    o.textContent = unsaved ? `${file} \u25CF` : file;
    o.dataset.unsaved = unsaved ? "yes" : "no";
  }
}

export function anyUnsaved() {
  return [...$("#file").options].some((o) => o.dataset.unsaved === "yes");
}

// The folder's files into the list, the open one selected; none open: a first entry asks for one.
export async function refreshFileList() {
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
