// The editor's language features (completion, hover, F12), each answered by the studio's language server.
import { hoverTooltip } from "@codemirror/view";
import { api } from "./api.js";
import { hooks } from "./hooks.js";
import { markdownToNodes } from "./markdown.js";
import { setStatus } from "./page.js";
import { state } from "./state.js";

// What `sandpaper lsp` gives an editor, asked of the studio (POST /api/language), which answers with
// the language server's own code for the text it holds: so first the typed text reaches it.
async function language(feature, doc, pos) {
  state.languageAsked++;  // in flight (shown to tests: asking again would cancel the question on its way)
  try {
    await hooks.flushCompile();
    await state.compiling;
    const line = doc.lineAt(pos);
    return await api("POST", "/api/language", { feature, line: line.number - 1, character: pos - line.from });
  } finally {
    state.languageAsked--;
  }
}

const completionTypes = { 14: "keyword", 12: "constant", 11: "unit", 9: "namespace" };
// Completion: statement keywords, library names after `like` (with what each describes), levels
// after `roughness`, units after a number. The server gives every candidate for the place; the
// editor filters them by what is typed.
export async function lspCompletion(context) {
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
export const lspHover = hoverTooltip(async (view, pos) => {
  let r;
  try {
    r = await language("hover", view.state.doc, pos);
  } catch {
    return null;
  }
  const value = r?.contents?.value ?? (typeof r?.contents === "string" ? r.contents : "");
  if (!value) return null;
  // A `like` name's entry comes as Markdown prose; explain's line as a ```text block, kept verbatim.
  const prose = r.contents.kind === "markdown" && !value.startsWith("```");
  return {
    pos,
    above: true,
    create() {
      if (prose) return { dom: markdownToNodes(value) };
      const dom = document.createElement("pre");
      dom.className = "hover";
      dom.textContent = value.replace(/^```text\n/, "").replace(/\n?```\s*$/, "");
      return { dom };
    },
  };
});

// Go to definition (F12): the library entry a `like` names, said in the status line.
export async function goToDefinition(view) {
  const r = await language("definition", view.state.doc, view.state.selection.main.head).catch(() => null);
  if (!r || !r.uri) { setStatus("no definition here: F12 on a library name after `like`"); return; }
  const file = decodeURIComponent(r.uri.replace(/^file:\/\//, ""));
  setStatus(`defined in ${file}, line ${r.range.start.line + 1}`);
  document.body.dataset.definition = file;
}
