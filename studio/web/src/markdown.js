// The little Markdown the language server's hovers use (paragraphs, **bold**, `code`), as DOM nodes:
// the page shows what a Markdown client shows, never the asterisks and backticks. Text only, no HTML.
export function markdownToNodes(md) {
  const out = document.createElement("div");
  out.className = "hover markdown";
  for (const para of md.split(/\n{2,}/)) {
    if (!para.trim()) continue;
    const p = document.createElement("p");
    // Tokens: `code`, **bold**, or plain text up to the next of either.
    for (const m of para.matchAll(/`([^`]+)`|\*\*([^*]+)\*\*|([^`*]+|[`*])/g)) {
      if (m[1] !== undefined) {
        const c = document.createElement("code");
        c.textContent = m[1];
        p.append(c);
      } else if (m[2] !== undefined) {
        const b = document.createElement("strong");
        b.textContent = m[2];
        p.append(b);
      } else {
        p.append(document.createTextNode(m[3]));
      }
    }
    out.append(p);
  }
  return out;
}
