// The studio's state events (/api/events): the live servo figures, the force strip, the hand on the
// stage, and following the text when it changes elsewhere.
import { api } from "./api.js";
import { applyCompile } from "./compile.js";
import { editor, setText } from "./editor.js";
import { refreshFileList } from "./file-list.js";
import { loadCurrent } from "./files.js";
import { drawOverlay } from "./overlay.js";
import { $, setStatus } from "./page.js";
import { state } from "./state.js";

// The studio owns the text: a change made elsewhere (the HTTP API, another tab) arrives with the
// state events as a higher text_version, and the page takes the studio's text and figures, unless
// its own edit is on its way (then that edit's answer brings them).
let following = false;
async function followDocument(d) {
  if (!d || following || !d.file) return;
  const behind = d.file !== state.file || d.text_version > (state.textVersion || 0);
  if (!state.file && behind) {  // a file opened elsewhere (another tab, the API) while none was open here
    following = true;
    try { await loadCurrent(); await refreshFileList(); } finally { following = false; }
    return;
  }
  if (!behind || state.compileTimer || state.opening || document.body.dataset.sliderBusy === "yes") return;
  following = true;
  try {
    // What the page had sent when it set out: an edit typed (or a slider moved) while the studio's
    // text was being fetched is newer than that text, and taking the fetched text would drop it.
    const sentBefore = state.sentText, compilingBefore = state.compiling;
    await state.compiling;
    const cur = await api("GET", "/api/current");
    if (state.sentText !== sentBefore || state.compiling !== compilingBefore || document.body.dataset.sliderBusy === "yes")
      return;  // the page's own edit is on its way; its answer brings the studio's text and figures
    // An open begun meanwhile loads the file itself; a second load beside it could land after an edit.
    if (state.opening) return;
    if (state.compileTimer || editor.state.doc.toString() !== state.sentText && cur.file === state.file) return;
    if (cur.file !== state.file) {
      await loadCurrent();
    } else {
      setText(cur.text);
      applyCompile({ ...cur.compile, parameters: cur.parameters, version: cur.version, saved: cur.saved,
                     text_version: cur.text_version });
    }
  } catch (e) {
    setStatus(e.message, true);
  } finally {
    following = false;
  }
}

function onState(s) {
  state.live = s;
  followDocument(s.document);
  // Which program plays, beside the text: a text that does not compile leaves an older one playing.
  const d = s.document;
  document.body.dataset.playingVersion = s.material_version;
  $("#playing-what").textContent = state.kind === "scene"
    ? "felt by the simulated 3-D device: drag on the view"
    : d && s.material_version
    ? (d.compiles && d.version === s.material_version ? `playing this text (v${s.material_version})`
                                                      : `playing v${s.material_version}, an earlier text`)
    : "";
  $("#rate").textContent = s.rate_hz.toFixed(1);
  $("#ticks").textContent = s.ticks;
  $("#overruns").textContent = s.overruns;
  $("#force").textContent = Math.hypot(s.force_N[0], s.force_N[1]).toFixed(3);
  $("#felt").textContent = s.felt_max_lateral_force_N.toFixed(3);
  $("#playing").textContent = s.material ? `${s.material} (v${s.material_version})` : "nothing yet";
  $("#servo").textContent = s.running ? "running" : `stopped: ${s.stop_cause}`;
  state.strip.push(Math.hypot(s.force_N[0], s.force_N[1]));
  if (state.strip.length > 300) state.strip.shift();
  drawStrip();
  if (state.kind === "material") drawOverlay();
  else if (state.kind === "workspace") drawWorkspaceHand();
}

function drawWorkspaceHand() {
  drawOverlay();
}

function drawStrip() {
  const c = $("#strip");
  const g = c.getContext("2d");
  g.clearRect(0, 0, c.width, c.height);
  const top = Math.max(0.05, ...state.strip, state.live?.compiled_max_lateral_force_N || 0);
  g.strokeStyle = "#8a4b08";
  g.lineWidth = 1.5;
  g.beginPath();
  state.strip.forEach((v, i) => {
    const x = (i / 299) * c.width, y = c.height - 4 - (v / top) * (c.height - 8);
    if (i) g.lineTo(x, y); else g.moveTo(x, y);
  });
  g.stroke();
  $("#strip-scale").textContent = `|F|, last 10 s, 0 to ${top.toFixed(2)} N`;
}

export function connectEvents() {
  const es = new EventSource("/api/events");
  es.onmessage = (e) => onState(JSON.parse(e.data));
  es.onerror = () => setStatus("lost the studio's event stream; retrying", true);
  // Said over nothing or over the lost stream's message, not over a message the page has to tell.
  es.onopen = () => { if (!$("#status").textContent || $("#status").classList.contains("bad")) setStatus("connected"); };
}
