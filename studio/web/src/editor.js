// The CodeMirror editor the page's text is typed in, and the way the studio's text gets into it.
import { EditorView, basicSetup } from "codemirror";
import { EditorState } from "@codemirror/state";
import { lintGutter } from "@codemirror/lint";
import { hmatLanguage } from "./hmat.js";
import { hooks } from "./hooks.js";
import { goToDefinition, lspCompletion, lspHover } from "./language.js";
import { $ } from "./page.js";
import { state } from "./state.js";

export const editorExtensions = [
  basicSetup, hmatLanguage, lintGutter(),
  EditorView.updateListener.of((u) => {
    if (!u.docChanged || state.remote) return;
    state.edits++;
    clearTimeout(state.compileTimer);
    // Short enough that diagnostics follow typing within 150 ms, long enough to skip keystrokes
    // typed in one burst.
    state.compileTimer = setTimeout(hooks.compileNow, 30);
  }),
  EditorView.domEventHandlers({
    keydown: (e, view) => {
      if ((e.ctrlKey || e.metaKey) && e.key === "s") { e.preventDefault(); hooks.save(); return true; }
      if (e.key === "F12") { e.preventDefault(); goToDefinition(view); return true; }
      return false;
    },
  }),
  EditorState.languageData.of(() => [{ autocomplete: lspCompletion }]),
  lspHover,
];
export const editor = new EditorView({ parent: $("#editor"), state: EditorState.create({ doc: "", extensions: editorExtensions }) });

// The studio's text into the editor (it is the studio's, so it is not sent back).
export function setText(text) {
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
