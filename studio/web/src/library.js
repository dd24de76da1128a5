// The library browser: search the library (its SQLite index, as `sandpaper library search`), see an
// entry's numbers and picture, insert `like NAME` into the text, or read the entry's file (read-only:
// it is the library's).
import { api } from "./api.js";
import { editor } from "./editor.js";
import { likeEdit } from "./insert-like.js";
import { $, roughnessText, setStatus } from "./page.js";
import { state } from "./state.js";

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
  $("#library-text").dataset.shown = e.name;
  $("#library-text").hidden = true;
}

// An entry's file, read-only, with the line at `line` (1-based) marked: where a diagnostic from it points.
export async function showEntryFile(name, line) {
  await showLibraryEntry(name);
  const pre = $("#library-text");
  if ($("#library-entry").dataset.name !== pre.dataset.shown) return;
  pre.hidden = false;
  const lines = pre.textContent.split("\n");
  if (line >= 1 && line <= lines.length) {
    const mark = document.createElement("mark");
    mark.textContent = lines[line - 1];
    pre.replaceChildren(lines.slice(0, line - 1).map((l) => l + "\n").join(""), mark, "\n" + lines.slice(line).join("\n"));
    mark.scrollIntoView({ block: "center" });
  } else {
    pre.scrollIntoView({ block: "nearest" });
  }
}

function insertLike() {
  const name = $("#library-entry").dataset.name;
  if (!name) return;
  const e = likeEdit(editor.state.doc.toString(), editor.state.selection.main.head, name, state.kind);
  if (e.why) { setStatus(`like ${name} not inserted: ${e.why}`, true); return; }
  editor.dispatch({ changes: { from: e.from, to: e.to, insert: e.insert }, selection: { anchor: e.cursor }, scrollIntoView: true });
  setStatus(e.message);
  editor.focus();
}

export function setupLibrary() {
  $("#library-search").addEventListener("input", () => { clearTimeout(librarySearchTimer); librarySearchTimer = setTimeout(searchLibrary, 150); });
  $("#library-insert").addEventListener("click", insertLike);
  $("#library-read").addEventListener("click", () => { $("#library-text").hidden = !$("#library-text").hidden; });
}
