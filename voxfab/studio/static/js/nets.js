// Nets on canvases: the gallery's thumbnails, with the marks of edges to cut or keep folded. An edge
// is named by its two faces [x, y, z, "+z"], as the net engine's EdgeConstraints and
// `voxfab net --constraints` name it. The chosen net is edited in the linked view of netview.js.

const FOLD_STYLE = {
  1: {color: '#ff00ff', dash: [5, 3]}, // mountain
  '-1': {color: '#00a000', dash: [6, 2, 1.5, 2]}, // valley
  0: {color: '#d0d0d0', dash: []}, // flat
};

function faceKey(f) { return f.join(','); }
function pairKey(a, b) { const x = faceKey(a), y = faceKey(b); return x < y ? `${x}|${y}` : `${y}|${x}`; }

export function foldSet(layout) {
  const s = new Set();
  const fo = layout.folds;
  for (let i = 0; i < fo.length; i += 2) s.add(fo[i] < fo[i + 1] ? `${fo[i]}-${fo[i + 1]}` : `${fo[i + 1]}-${fo[i]}`);
  return s;
}

function frame(layout, W, H, pad) {
  const c = layout.corners;
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (let i = 0; i < c.length; i += 2) {
    x0 = Math.min(x0, c[i]); x1 = Math.max(x1, c[i]); y0 = Math.min(y0, c[i + 1]); y1 = Math.max(y1, c[i + 1]);
  }
  const s = Math.min((W - 2 * pad) / (x1 - x0), (H - 2 * pad) / (y1 - y0));
  const ox = pad + (W - 2 * pad - s * (x1 - x0)) / 2, oy = pad + (H - 2 * pad - s * (y1 - y0)) / 2;
  return {s, toScreen: (x, y) => [ox + (x - x0) * s, H - oy - (y - y0) * s],
    toNet: (px, py) => [(px - ox) / s + x0, (H - oy - py) / s + y0]};
}

// Draw a net: faces, cut edges red, folds by type, and the marks (cut: thick red, keep: thick blue).
export function drawNet(canvas, layout, marks = null) {
  const ctx = canvas.getContext('2d'), W = canvas.width, H = canvas.height;
  ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, W, H);
  const {s, toScreen} = frame(layout, W, H, 6);
  const c = layout.corners, F = layout.faces.length, folds = foldSet(layout);
  ctx.fillStyle = '#fbf1e2';
  for (let i = 0; i < F; i++) {
    ctx.beginPath();
    for (let k = 0; k < 4; k++) ctx[k ? 'lineTo' : 'moveTo'](...toScreen(c[8 * i + 2 * k], c[8 * i + 2 * k + 1]));
    ctx.closePath(); ctx.fill();
  }
  const lw = Math.max(0.5, Math.min(2, s / 8));
  const cuts = new Path2D();
  for (let i = 0; i < F; i++) {
    for (let k = 0; k < 4; k++) {
      const j = layout.neighbor[4 * i + k];
      const a = toScreen(c[8 * i + 2 * k], c[8 * i + 2 * k + 1]);
      const b = toScreen(c[8 * i + 2 * ((k + 1) % 4)], c[8 * i + 2 * ((k + 1) % 4) + 1]);
      if (folds.has(i < j ? `${i}-${j}` : `${j}-${i}`)) {
        if (i > j) continue; // once per fold
        const st = FOLD_STYLE[layout.fold_type[4 * i + k]] || FOLD_STYLE[0];
        ctx.strokeStyle = st.color; ctx.lineWidth = lw * 0.8; ctx.setLineDash(s > 6 ? st.dash : []);
        ctx.beginPath(); ctx.moveTo(...a); ctx.lineTo(...b); ctx.stroke();
      } else {
        cuts.moveTo(...a); cuts.lineTo(...b);
      }
    }
  }
  ctx.setLineDash([]); ctx.strokeStyle = '#ff0000'; ctx.lineWidth = lw; ctx.stroke(cuts);
  if (marks && marks.size) {
    ctx.lineCap = 'round'; ctx.lineWidth = Math.max(3, lw * 3);
    for (let i = 0; i < F; i++) {
      for (let k = 0; k < 4; k++) {
        const j = layout.neighbor[4 * i + k];
        const m = marks.get(pairKey(layout.faces[i], layout.faces[j]));
        if (!m) continue;
        ctx.strokeStyle = m.state === 'cut' ? 'rgba(220,0,0,0.75)' : 'rgba(0,90,220,0.75)';
        ctx.beginPath();
        ctx.moveTo(...toScreen(c[8 * i + 2 * k], c[8 * i + 2 * k + 1]));
        ctx.lineTo(...toScreen(c[8 * i + 2 * ((k + 1) % 4)], c[8 * i + 2 * ((k + 1) % 4) + 1]));
        ctx.stroke();
      }
    }
    ctx.lineCap = 'butt';
  }
}
