// The compiler's diagnostics, shown twice: marked in the editor and listed under it.
import { setDiagnostics } from "@codemirror/lint";
import { editor } from "./editor.js";
import { $ } from "./page.js";

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
