// Small helpers every part of the page uses: the element lookup, the status line, and roughness as
// Sandpaper prints it.
export const $ = (sel) => document.querySelector(sel);

// A roughness as every Sandpaper output prints it: three significant digits (schema::roughness_text).
export function roughnessText(r) { return String(Number(r.toPrecision(3))); }

export function setStatus(text, bad = false) {
  const s = $("#status");
  s.textContent = text;
  s.title = text;  // the whole of it, when the header's one line cuts it short
  s.classList.toggle("bad", bad);
}
