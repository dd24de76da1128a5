// The canvas over the picture: the field's arrows, and the hand with the force on it.
import { $ } from "./page.js";
import { toPx } from "./stage.js";
import { state } from "./state.js";

export function drawOverlay() {
  const canvas = $("#overlay");
  const stage = $("#stage");
  const r = stage.getBoundingClientRect();
  if (canvas.width !== Math.round(r.width) || canvas.height !== Math.round(r.height)) {
    canvas.width = Math.round(r.width);
    canvas.height = Math.round(r.height);
  }
  const g = canvas.getContext("2d");
  g.clearRect(0, 0, canvas.width, canvas.height);
  // Field arrows (materials): where and which way a slow hand is pushed.
  const f = state.field;
  if (state.kind === "material" && !state.zoom && f && f.n && f.max_N > 0 && $("#arrows").checked) {
    g.strokeStyle = "rgba(30, 90, 200, 0.7)";
    g.lineWidth = 1;
    const cell = canvas.width / f.n;
    for (let row = 0; row < f.n; row++) for (let col = 0; col < f.n; col++) {
      const i = row * f.n + col;
      const fx = f.fx_N[i] / f.max_N, fy = f.fy_N[i] / f.max_N;
      const cx = (col + 0.5) * cell, cy = (row + 0.5) * (canvas.height / f.n);
      arrow(g, cx, cy, cx + fx * cell * 0.45, cy - fy * cell * 0.45, 3);
    }
  }
  const live = state.live;
  if (!live) return;
  const [hx, hy] = toPx(live.hand[0], live.hand[1], r);
  const scale = 80 / Math.max(live.compiled_max_lateral_force_N || 1, 0.05);  // the compiled maximum is 80 px
  const fx = live.force_N[0] * scale, fy = live.force_N[1] * scale;
  g.beginPath();
  g.arc(hx, hy, 7, 0, 2 * Math.PI);
  g.lineWidth = 2;
  g.strokeStyle = "#111";
  g.fillStyle = "rgba(255, 210, 60, 0.9)";
  g.fill();
  g.stroke();
  // The force on the hand, from its centre, drawn over it.
  g.strokeStyle = "#c0392b";
  g.fillStyle = "#c0392b";
  g.lineWidth = 3;
  arrow(g, hx, hy, hx + fx, hy - fy, 9);
  stage.dataset.hand = `${live.hand[0].toFixed(3)},${live.hand[1].toFixed(3)}`;
  stage.dataset.force = `${live.force_N[0].toFixed(4)},${live.force_N[1].toFixed(4)}`;
  stage.dataset.handPx = `${hx.toFixed(1)},${hy.toFixed(1)}`;
  stage.dataset.arrowPx = `${(hx + fx).toFixed(1)},${(hy - fy).toFixed(1)}`;
}

function arrow(g, x0, y0, x1, y1, head) {
  g.beginPath();
  g.moveTo(x0, y0);
  g.lineTo(x1, y1);
  g.stroke();
  const len = Math.hypot(x1 - x0, y1 - y0);
  if (len < 2) return;
  const ux = (x1 - x0) / len, uy = (y1 - y0) / len;
  g.beginPath();
  g.moveTo(x1, y1);
  g.lineTo(x1 - head * ux + head * 0.5 * uy, y1 - head * uy - head * 0.5 * ux);
  g.lineTo(x1 - head * ux - head * 0.5 * uy, y1 - head * uy + head * 0.5 * ux);
  g.closePath();
  g.fill();
}
