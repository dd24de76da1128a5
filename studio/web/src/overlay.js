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
  // Field arrows (materials): each cell's strongest push on a slow hand, drawn from where it is, its
  // length |F| on the one scale the legend gives in newtons.
  const f = state.field;
  delete stage.dataset.arrowScaleN;
  if (state.kind === "material" && !state.zoom && f && f.n && f.max_N > 0 && f.x_mm && $("#arrows").checked) {
    const full = 0.9 * Math.min(canvas.width / f.n, canvas.height / f.n);  // the strongest arrow, px
    g.lineWidth = 1.5;
    for (let i = 0; i < f.fx_N.length; i++) {
      const mag = Math.hypot(f.fx_N[i], f.fy_N[i]);
      if (mag < 0.02 * f.max_N) continue;  // under a pixel or two: a dot would only add noise
      const [x0, y0] = toPx(f.x_mm[i], f.y_mm[i], r);
      const k = full / f.max_N;
      // A pale halo first, so that the arrow reads on the grey height field and the dark field alike.
      g.lineWidth = 4;
      g.strokeStyle = g.fillStyle = "rgba(255, 255, 255, 0.75)";
      arrow(g, x0, y0, x0 + f.fx_N[i] * k, y0 - f.fy_N[i] * k, 6);
      g.lineWidth = 1.5;
      g.strokeStyle = g.fillStyle = "rgba(20, 70, 190, 0.95)";
      arrow(g, x0, y0, x0 + f.fx_N[i] * k, y0 - f.fy_N[i] * k, 4);
    }
    legend(g, canvas.width, full, f.max_N);
    stage.dataset.arrowScaleN = String(f.max_N);
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

// The arrows' scale, top right: the longest arrow and the force it stands for.
function legend(g, width, full, maxN) {
  const text = `= ${maxN.toPrecision(3)} N`;
  g.font = "12px system-ui, 'DejaVu Sans', sans-serif";
  const w = full + 10 + g.measureText(text).width + 12;
  const x = width - w - 6, y = 6;
  g.fillStyle = "rgba(255, 255, 255, 0.9)";
  g.fillRect(x, y, w, 20);
  g.strokeStyle = g.fillStyle = "rgba(20, 70, 190, 0.9)";
  g.lineWidth = 1.5;
  arrow(g, x + 6, y + 10, x + 6 + full, y + 10, 4);
  g.fillStyle = "#222";
  g.textBaseline = "middle";
  g.fillText(text, x + full + 14, y + 10.5);
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
