// The subject's page (docs/EXPERIMENTS.md, "The subject's page"). It long-polls /api/screen and
// shows one screen at a time; answers go to /api/answer with the screen's seq, so an answer can
// never land on the wrong trial. Keyboard and touch both work: Enter, the number keys, and taps or
// drags for sorting.
"use strict";

const main = document.getElementById("screen");
let seq = -1;
let seenSession = false;  // a session has served a screen to this page

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === "class") e.className = v;
    else if (k.startsWith("on")) e.addEventListener(k.slice(2), v);
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

async function answer(body, error) {
  const was = document.body.dataset.screen, answered = seq;
  document.body.dataset.screen = "sending";  // until the server has it: no second answer to this screen
  // The next screen may arrive (long poll) before this request's response: then it stays.
  const still = () => seq === answered;
  try {
    const r = await fetch("/api/answer", { method: "POST", headers: { "Content-Type": "application/json" },
      body: JSON.stringify({ seq: answered, ...body }) });
    if (!r.ok) {
      const j = await r.json().catch(() => ({ error: r.statusText }));
      if (still()) {
        if (error) error.textContent = j.error;
        document.body.dataset.screen = was;
      }
      return false;
    }
    if (still()) {
      main.replaceChildren(el("p", { class: "big" }, "\u2026"));
      document.body.dataset.screen = "sent";
    }
    return true;
  } catch (e) {
    if (still()) {
      if (error) error.textContent = "cannot reach the experiment: " + e;
      document.body.dataset.screen = was;
    }
    return false;
  }
}

function trialLine(s) {
  return el("p", { class: "note" }, s.practice ? `practice trial ${s.trial}` : `trial ${s.trial}`);
}

function continueScreen(heading, text, label) {
  const error = el("p", { class: "error" });
  const go = el("button", { class: "primary", type: "button", id: "continue", onclick: () => answer({ continue: true }, error) }, label);
  main.replaceChildren(el("h1", {}, heading), text, go, error);
  go.focus();
}

function numberScreen(s, question, hint, confidence) {
  const error = el("p", { class: "error" });
  const input = el("input", { class: "answer", id: "value", inputmode: "decimal", autocomplete: "off", "aria-label": question });
  let slider = null;
  if (confidence) {
    slider = el("input", { type: "range", min: "0", max: "100", step: "1", value: "50", id: "slider", "aria-label": question });
    input.value = "50";
    slider.addEventListener("input", () => { input.value = slider.value; });
    input.addEventListener("input", () => { if (input.value !== "" && isFinite(+input.value)) slider.value = input.value; });
  }
  const send = () => {
    const v = Number(input.value.trim().replace(",", "."));
    if (input.value.trim() === "" || !isFinite(v) || (confidence ? v < 0 || v > 100 : v <= 0)) {
      error.textContent = confidence ? "Please give a number from 0 to 100." : "Please give a positive number.";
      return;
    }
    answer({ value: v }, error);
  };
  input.addEventListener("keydown", (e) => { if (e.key === "Enter") send(); });
  const done = el("button", { class: "primary", type: "button", id: "done", onclick: send }, "Done");
  main.replaceChildren(trialLine(s), el("h1", {}, question), el("p", { class: "note" }, hint),
    ...(slider ? [slider] : []), input, done, error);
  input.focus();
}

function intervalScreen(s) {
  const error = el("p", { class: "error" });
  const choice = (n, word) => el("button", { type: "button", id: `interval-${n}`, onclick: () => answer({ interval: n }, error) },
    String(n), el("small", {}, word));
  main.replaceChildren(trialLine(s), el("h1", {}, "Which felt stronger?"),
    el("p", { class: "note" }, "Press 1 or 2, or tap."), el("div", { class: "choices" }, choice(1, "first"), choice(2, "second")), error);
}

// Sorting (thesis 6.2.5): numbered patches into piles, by dragging, or by tapping a patch then a pile.
function sortScreen(s) {
  const error = el("p", { class: "error" });
  const tray = el("div", { class: "tray", id: "tray", "data-pile": "0", role: "button", tabindex: "0", "aria-label": "unsorted patches" });
  const piles = [];
  let selected = null;
  // Tap (or Enter on) a pile or the tray to put the selected patch there.
  const targetable = (area) => {
    area.addEventListener("click", () => { if (selected) place(selected, area); });
    area.addEventListener("keydown", (e) => {
      if ((e.key === "Enter" || e.key === " ") && e.target === area && selected) { e.preventDefault(); place(selected, area); }
    });
  };
  targetable(tray);
  const place = (tile, pile) => {
    pile.append(tile);
    tile.classList.remove("selected");
    selected = null;
    done.disabled = tray.children.length > 0;
  };
  for (let p = 1; p <= s.piles; p++) {
    // A div acting as a button: a <button> may not hold the patches' buttons.
    const pile = el("div", { class: "pile", role: "button", tabindex: "0", id: `pile-${p}`, "data-pile": String(p),
      "aria-label": `pile ${p}` }, el("span", { class: "label" }, `pile ${p}`));
    targetable(pile);
    piles.push(pile);
  }
  for (let i = 1; i <= s.patches; i++) {
    const tile = el("button", { class: "tile", type: "button", id: `patch-${i}`, "data-patch": String(i),
      "aria-label": `patch ${i}` }, String(i));
    tile.addEventListener("click", (e) => {
      e.stopPropagation();
      // A tap on a patch lying in another pile puts the selected patch into that pile.
      if (selected && selected !== tile && tile.parentElement !== selected.parentElement) {
        place(selected, tile.parentElement);
        return;
      }
      if (selected) selected.classList.remove("selected");
      selected = selected === tile ? null : tile;
      if (selected) selected.classList.add("selected");
    });
    tile.addEventListener("pointerdown", (e) => startDrag(e, tile));
    tray.append(tile);
  }
  function startDrag(e, tile) {
    const x0 = e.clientX, y0 = e.clientY;
    let moved = false;
    const move = (m) => {
      if (!moved && Math.hypot(m.clientX - x0, m.clientY - y0) < 6) return;
      if (!moved) { moved = true; tile.classList.add("dragging"); }
      tile.style.left = `${m.clientX - 40}px`;
      tile.style.top = `${m.clientY - 40}px`;
      for (const p of [tray, ...piles]) p.classList.toggle("target", p === under(m));
    };
    const up = (u) => {
      window.removeEventListener("pointermove", move);
      window.removeEventListener("pointerup", up);
      if (!moved) return;
      tile.classList.remove("dragging");
      tile.style.left = tile.style.top = "";
      const target = under(u);
      for (const p of [tray, ...piles]) p.classList.remove("target");
      if (target) place(tile, target);
    };
    window.addEventListener("pointermove", move);
    window.addEventListener("pointerup", up);
  }
  function under(ev) {
    for (const p of [tray, ...piles]) {
      const r = p.getBoundingClientRect();
      if (ev.clientX >= r.left && ev.clientX <= r.right && ev.clientY >= r.top && ev.clientY <= r.bottom) return p;
    }
    return null;
  }
  const done = el("button", { class: "primary", type: "button", id: "done", disabled: "" }, "Done");
  done.addEventListener("click", () => {
    const assignment = [];
    for (let i = 1; i <= s.patches; i++) assignment.push(Number(document.getElementById(`patch-${i}`).parentElement.dataset.pile));
    if (assignment.includes(0)) { error.textContent = "Put every patch in a pile."; return; }
    for (let p = 1; p <= s.piles; p++)
      if (!assignment.includes(p)) { error.textContent = `Pile ${p} is empty: use every pile.`; return; }
    answer({ assignment }, error);
  });
  main.replaceChildren(el("h1", {}, `Sort the patches into ${s.piles} groups of similar roughness`),
    el("p", { class: "note" }, "Drag each numbered patch onto a pile, or tap a patch and then a pile."),
    tray, el("div", { class: "piles" }, ...piles), done, error);
}

function render(s) {
  document.body.dataset.screen = s.kind;
  document.body.dataset.seq = String(s.seq);
  switch (s.kind) {
    case "instructions":
      // One <p> per paragraph, its lines flowing: the design's hard line breaks are the editor's, not the subject's.
      continueScreen(s.title, el("div", { class: "instructions" }, ...(s.paragraphs || [s.text.trim()]).map((t) => el("p", {}, t))), "Begin");
      break;
    case "feel": {
      const what = s.patches > 1 ? "Feel each patch as it plays" : "Feel the surface";
      main.replaceChildren(el("p", { class: "note" }, s.practice ? `practice trial ${s.trial} of ${s.total}` : `trial ${s.trial} of ${s.total}`),
        el("p", { class: "big" }, what));
      break;
    }
    case "estimate":
      numberScreen(s, s.question || "How rough was it?", s.hint || "Any positive number: larger for rougher.", false);
      break;
    case "confidence":
      numberScreen(s, "Was it a textured surface?", "How confident are you, from 0 (not at all) to 100 (certain)?", true);
      break;
    case "interval":
      intervalScreen(s);
      break;
    case "sort":
      sortScreen(s);
      break;
    case "rest":
      continueScreen("Time for a rest", el("p", {}, `${s.done} of ${s.total} trials done. Continue when you are ready.`), "Continue");
      break;
    case "done":
      main.replaceChildren(el("p", { class: "big" }, "Thank you. That is all."));
      break;
    case "paused":
      main.replaceChildren(el("p", { class: "big" }, "Paused. Please wait for the experimenter."));
      break;
    default:
      main.replaceChildren(el("p", { class: "big" }, "Please wait\u2026"));
  }
}

document.addEventListener("keydown", (e) => {
  const kind = document.body.dataset.screen;
  if (kind === "interval" && (e.key === "1" || e.key === "2")) document.getElementById(`interval-${e.key}`).click();
  else if ((kind === "instructions" || kind === "rest") && e.key === "Enter") {
    e.preventDefault();  // the focused button would take the Enter too: one answer, not two
    document.getElementById("continue").click();
  }
});

document.getElementById("fullscreen").addEventListener("click", () => {
  if (document.fullscreenElement) document.exitFullscreen();
  else document.documentElement.requestFullscreen().catch(() => {});
});

async function poll() {
  for (;;) {
    try {
      const r = await fetch(`/api/screen?after=${seq}`, { cache: "no-store" });
      const s = await r.json();
      if (s.seq !== seq) { seq = s.seq; render(s); }
      seenSession = true;
    } catch (e) {
      // The session has ended (its last screen stays up), or is not running yet: try again, and
      // start from the first screen when a resumed session answers. A session that goes away in
      // the middle (killed, the power gone) could not send "paused": the page says it itself.
      const kind = document.body.dataset.screen;
      if (kind !== "done" && kind !== "paused") {
        if (seenSession) render({ kind: "paused", seq: -1 });
        else {
          document.body.dataset.screen = "offline";
          main.replaceChildren(el("p", { class: "big" }, "Waiting for the experiment\u2026"));
        }
      }
      seq = -1;
      await new Promise((ok) => setTimeout(ok, 1000));
    }
  }
}
poll();
