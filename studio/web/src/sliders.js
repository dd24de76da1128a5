// A slider for each number in the text that can be tuned; moving one edits the text in the studio.
import { api } from "./api.js";
import { setText } from "./editor.js";
import { hooks } from "./hooks.js";
import { $, setStatus } from "./page.js";
import { state } from "./state.js";

export function renderSliders(params) {
  const box = $("#sliders");
  const same = params.length === state.parameters.length && params.every((p, i) => p.name === state.parameters[i].name);
  state.parameters = params;
  if (!same) {
    box.replaceChildren();
    for (const p of params) {
      const row = document.createElement("label");
      row.className = "slider " + p.layer;
      row.innerHTML = `<span class="name"></span><input type="range"><output></output>`;
      row.querySelector(".name").textContent = p.label;
      const input = row.querySelector("input");
      input.dataset.name = p.name;
      input.addEventListener("input", () => sliderMoved(input));
      box.append(row);
    }
    if (!params.length) box.textContent = "No numbers to tune in this text.";
  }
  box.querySelectorAll("input[type=range]").forEach((input, i) => {
    const p = params[i];
    if (sliderSends.get(p.name)?.busy) return;  // the hand is on it: leave it where the hand put it
    input.min = p.min; input.max = p.max; input.step = p.step; input.value = p.value;
    input.dataset.unit = p.unit;
    input.nextElementSibling.textContent = `${p.value} ${p.unit}`.trim();
  });
}

// While a slider moves, its value goes to the studio at once when no request is in flight, else as
// soon as the one in flight returns (only the latest value): the material follows the hand on the
// slider, and the last value arrives one round trip after the last move.
const sliderSends = new Map();
function sliderMoved(input) {
  const name = input.dataset.name;
  const step = input.step.includes(".") ? input.step.split(".")[1].length : 0;
  const value = Number(Number(input.value).toFixed(step));
  input.nextElementSibling.textContent = `${value} ${input.dataset.unit}`.trim();
  const s = sliderSends.get(name) || { busy: false, next: null };
  sliderSends.set(name, s);
  s.next = value;
  if (!s.busy) sendSlider(name, input.dataset.unit, s);
}

async function sendSlider(name, unit, s) {
  s.busy = true;
  document.body.dataset.sliderBusy = "yes";
  while (s.next !== null) {
    const value = s.next;
    s.next = null;
    try {
      const r = await api("POST", "/api/parameter", { name, value, unit });
      setText(r.text);
      hooks.applyCompile(r, true);
    } catch (e) {
      setStatus(e.message, true);
    }
  }
  s.busy = false;
  if (![...sliderSends.values()].some((x) => x.busy)) document.body.dataset.sliderBusy = "no";
}
