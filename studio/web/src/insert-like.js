// Where "insert like NAME" goes in a material's text: a `like` already there is replaced (a second
// would be E0302, two entries to start from); otherwise the line goes inside the `material { }`
// block, after the cursor's line when that lies in the block, else first in it. A pure function of
// the text, so that it is the same wherever it is asked.

// The text of each line with its comment and strings blanked, so that a `{` or `like` inside them
// is not taken for the block or the statement.
function code(line) {
  return line.replace(/"(?:[^"\\]|\\.)*"?/g, (s) => " ".repeat(s.length)).replace(/#.*/, "");
}

// text: the editor's text; head: the cursor's offset; name: the entry. Returns {from, to, insert,
// cursor, message} (a change to make, and what to say), or {why} when nothing should change.
export function likeEdit(text, head, name, kind = "material") {
  if (kind === "workspace")
    return { why: `a workspace places patches: write patch "${name}" at X, Y, or open a material to start it from ${name}` };
  if (kind === "scene")
    return { why: `a scene names a material on each object: write material "${name}" in the object's block` };
  const lines = text.split("\n");
  const starts = [];
  let at = 0;
  for (const l of lines) { starts.push(at); at += l.length + 1; }
  // The `like` statements, each at its line (a `;` may join statements on one line).
  for (let i = 0; i < lines.length; i++) {
    const c = code(lines[i]);
    const m = /(^|[;{]\s*|^\s*)like\s+([^\s;#}]+)/.exec(c);
    if (!m) continue;
    const nameFrom = starts[i] + m.index + m[0].length - m[2].length;
    const nameTo = nameFrom + m[2].length;
    const old = text.slice(nameFrom, nameTo);
    if (old === name) return { why: `it is like ${name} already (line ${i + 1})` };
    return { from: nameFrom, to: nameTo, insert: name, cursor: nameFrom + name.length,
             message: `like ${old} on line ${i + 1} replaced by like ${name}: a material starts from one entry` };
  }
  // The block: from the line of the `{` after `material` to the line of its `}`.
  let open = -1, close = -1;
  for (let i = 0; i < lines.length; i++) {
    const c = code(lines[i]);
    if (open < 0 && /\bmaterial\b/.test(c) && c.includes("{")) open = i;
    if (open >= 0 && c.includes("}") && (i > open || c.indexOf("}") > c.indexOf("{"))) { close = i; break; }
  }
  const insert = `  like ${name}`;
  if (open < 0) {
    // Bare statements: after the cursor's line.
    const line = lines.findIndex((_, i) => head <= starts[i] + lines[i].length);
    const end = starts[line] + lines[line].length;
    return { from: end, to: end, insert: "\n" + insert.trim(), cursor: end + insert.trim().length + 1,
             message: `inserted like ${name} on line ${line + 2}` };
  }
  if (close === open) {
    // `material "x" { ... }` on one line: the statement first in the block, `;`-separated.
    const brace = starts[open] + code(lines[open]).indexOf("{") + 1;
    const ins = ` like ${name};`;
    return { from: brace, to: brace, insert: ins, cursor: brace + ins.length - 1, message: `inserted like ${name} on line ${open + 1}` };
  }
  const cursorLine = lines.findIndex((_, i) => head <= starts[i] + lines[i].length);
  const after = cursorLine > open && (close < 0 || cursorLine < close) ? cursorLine : open;
  const end = starts[after] + lines[after].length;
  return { from: end, to: end, insert: "\n" + insert, cursor: end + 1 + insert.length,
           message: `inserted like ${name} on line ${after + 2}` };
}
