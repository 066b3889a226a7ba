// Nets on canvases: the gallery's thumbnails, with the marks of edges to cut or keep folded. An edge
// is named by its two faces [x, y, z, "+z"], as the net engine's EdgeConstraints and
// `voxfab net --constraints` name it. The chosen net is edited in the linked view of netview.js.

import {sheetRect} from './sheets.js';

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

// The bounds [x0, y0, x1, y1] of the faces `only` (all when null), in the layout's units.
function faceBounds(layout, only) {
  const c = layout.corners;
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (let i = 0; i < layout.faces.length; i++) {
    if (only && !only.has(i)) continue;
    for (let k = 8 * i; k < 8 * i + 8; k += 2) {
      x0 = Math.min(x0, c[k]); x1 = Math.max(x1, c[k]); y0 = Math.min(y0, c[k + 1]); y1 = Math.max(y1, c[k + 1]);
    }
  }
  return [x0, y0, x1, y1];
}

// Bounds [x0, y0, x1, y1] shown in the box [bx, by, bw, bh] of a canvas, centred, `pad` pixels in.
function frame([x0, y0, x1, y1], [bx, by, bw, bh], pad) {
  const s = Math.min((bw - 2 * pad) / (x1 - x0), (bh - 2 * pad) / (y1 - y0));
  const ox = bx + pad + (bw - 2 * pad - s * (x1 - x0)) / 2, oy = by + pad + (bh - 2 * pad - s * (y1 - y0)) / 2;
  const bottom = by + bh;
  return {s, toScreen: (x, y) => [ox + (x - x0) * s, bottom - (oy - by) - (y - y0) * s]};
}

// Draw a net: faces, cut edges red, folds by type, and the marks (cut: thick red, keep: thick blue).
// box: the part [x, y, w, h] of the canvas to draw in (all of it by default); only: the Set of faces to
// draw (all by default); bounds: what to fit in the box (the faces drawn by default, or a sheet, outlined).
// Returns the pixels of the canvas per face edge.
export function drawNet(canvas, layout, {marks = null, box = null, only = null, bounds = null} = {}) {
  const ctx = canvas.getContext('2d'), W = canvas.width, H = canvas.height;
  box = box || [0, 0, W, H];
  ctx.fillStyle = '#fff'; ctx.fillRect(...box);
  const {s, toScreen} = frame(bounds || faceBounds(layout, only), box, 6);
  const c = layout.corners, F = layout.faces.length, folds = foldSet(layout);
  if (bounds) { // the sheet's edge
    const [a, b] = [toScreen(bounds[0], bounds[3]), toScreen(bounds[2], bounds[1])];
    ctx.strokeStyle = '#c8c0b4'; ctx.lineWidth = 1; ctx.setLineDash([]);
    ctx.strokeRect(Math.round(a[0]) + 0.5, Math.round(a[1]) + 0.5, Math.round(b[0] - a[0]) - 1, Math.round(b[1] - a[1]) - 1);
  }
  const shown = (i) => !only || only.has(i);
  ctx.fillStyle = '#fbf1e2';
  for (let i = 0; i < F; i++) {
    if (!shown(i)) continue;
    ctx.beginPath();
    for (let k = 0; k < 4; k++) ctx[k ? 'lineTo' : 'moveTo'](...toScreen(c[8 * i + 2 * k], c[8 * i + 2 * k + 1]));
    ctx.closePath(); ctx.fill();
  }
  const lw = Math.max(0.5, Math.min(2, s / 8));
  const cuts = new Path2D();
  for (let i = 0; i < F; i++) {
    if (!shown(i)) continue;
    for (let k = 0; k < 4; k++) {
      const j = layout.neighbor[4 * i + k];
      const a = toScreen(c[8 * i + 2 * k], c[8 * i + 2 * k + 1]);
      const b = toScreen(c[8 * i + 2 * ((k + 1) % 4)], c[8 * i + 2 * ((k + 1) % 4) + 1]);
      if (folds.has(i < j ? `${i}-${j}` : `${j}-${i}`)) {
        if (i > j && shown(j)) continue; // once per fold
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
  return s;
}

// A gallery thumbnail of a net laid out on its sheets (`layout` as placedLayout gives it): the first sheet
// large, on its own, the others in a strip below it. Without a placement (a net that does not fit its
// sheet), the whole net. Returns the canvas pixels per face edge of the first sheet.
export function drawThumb(canvas, layout, placement) {
  const W = canvas.width, H = canvas.height;
  if (!placement) return drawNet(canvas, layout);
  const on = Array.from({length: placement.sheets}, () => new Set());
  for (let i = 0; i < layout.faces.length; i++) {
    on[placement.pieces[layout.piece ? layout.piece[i] : 0].sheet].add(i);
  }
  const rest = placement.sheets - 1, strip = rest ? Math.round(0.22 * H) : 0;
  const s = drawNet(canvas, layout, {box: [0, 0, W, H - strip], only: on[0], bounds: sheetRect(placement, 0)});
  for (let k = 1; k <= rest; k++) {
    const w = W / rest;
    drawNet(canvas, layout, {box: [(k - 1) * w, H - strip, w, strip], only: on[k], bounds: sheetRect(placement, k)});
  }
  return s;
}
