// The compiler's diagnostics, shown twice: marked in the editor and listed under it. One from a
// library entry's file (`file`) is marked where the open text brought it in (`brought_in`: the
// `like`, or the workspace's patch) and opens the entry's file when clicked.
import { setDiagnostics } from "@codemirror/lint";
import { editor } from "./editor.js";
import { showEntryFile } from "./library.js";
import { $ } from "./page.js";

// The place in the open text: its own line and column, or where a diagnostic from another file came in.
const place = (d) => d.brought_in || d;

function toEditorDiagnostics(list) {
  const doc = editor.state.doc;
  const out = [];
  for (const d of list) {
    const p = place(d);
    if (!p.line || p.line > doc.lines) continue;
    const line = doc.line(p.line);
    const from = Math.min(line.from + Math.max(0, p.column - 1), line.to);
    let to = from;
    if (d.brought_in) to = Math.min(from + Math.max(1, p.length || 1), line.to);
    else while (to < line.to && !/\s/.test(doc.sliceString(to, to + 1))) to++;
    if (to === from) to = Math.min(from + 1, doc.length);
    out.push({ from, to, severity: d.severity === "error" ? "error" : "warning",
               message: (d.file ? `${d.location}: ` : "") + `${d.code}: ${d.message}` + (d.suggestion ? `\nhelp: ${d.suggestion}` : "") });
  }
  return out;
}

export function showDiagnostics(list) {
  editor.dispatch(setDiagnostics(editor.state, toEditorDiagnostics(list)));
  const ul = $("#diagnostics");
  ul.replaceChildren();
  for (const d of list) {
    const li = document.createElement("li");
    li.className = d.severity;
    li.dataset.line = d.line;
    li.dataset.column = d.column;
    li.dataset.code = d.code;
    if (d.file) li.dataset.file = d.file;
    li.innerHTML = `<b></b> <span class="code">${d.code}</span> `;
    li.querySelector("b").textContent = d.file ? d.location : `${d.line}:${d.column}`;
    li.append(document.createTextNode(d.message));
    if (d.suggestion) {
      const help = document.createElement("div");
      help.className = "help";
      help.textContent = "help: " + d.suggestion;
      li.append(help);
    }
    li.addEventListener("click", () => {
      const p = place(d);
      const line = editor.state.doc.line(Math.min(Math.max(1, p.line), editor.state.doc.lines));
      editor.dispatch({ selection: { anchor: Math.min(line.from + Math.max(0, p.column - 1), line.to) }, scrollIntoView: true });
      if (d.entry) showEntryFile(d.entry, d.line);
      else editor.focus();
    });
    ul.append(li);
  }
  $("#diagnostics-title").textContent = list.length ? `Diagnostics (${list.length})` : "No diagnostics";
}
