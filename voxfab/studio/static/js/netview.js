// The chosen net in 2D, linked to the 3D view, and its fold-up.
//
// Wheel zooms about the pointer, a drag pans, hovering lights up a face or an edge here and the same
// face (or both halves of the seam, with its label) in the 3D view; a click on an edge cuts that fold
// or joins that seam through POST /api/nets/edit, which repairs the net around it and answers with
// the new layout. The fold slider and its play button fold the net from flat to the shape in the
// 3D view: each face turns about the edge it shares with its parent by a share of its fold angle,
// as voxfab/render/_fold.py does (fold_frames), so mountain and valley folds turn opposite ways.
// LAYOUT is the studio net contract's: faces, corners (2D, per piece), corners3d, folds, neighbor,
// fold_type, piece, parent, labels.

import {post} from './api.js';
import {faceColours} from './paint.js';
import {edgeKey, faceName} from './viewer.js';

const FOLD_STYLE = {
  1: {color: '#ff00ff', dash: [5, 3]}, // mountain
  '-1': {color: '#00a000', dash: [6, 2, 1.5, 2]}, // valley
  0: {color: '#c8c8c8', dash: []}, // flat
};
const GAP = 2; // faces between pieces side by side
const ROOM_BELOW = 230;
// A face at least this wide on screen, px: its edges can be clicked (a quarter face either side of them).
// A net smaller than that at its full view opens on its first piece, fitted; a piece at most MAX_FACE_PX.
const MIN_FACE_PX = 12, MAX_FACE_PX = 48; // px of the window the editor's canvas leaves for the page's header and its own controls

// --- 3×3 matrices, row-major arrays of 9 ---
const I3 = [1, 0, 0, 0, 1, 0, 0, 0, 1];
function mul(a, b) {
  const o = new Array(9);
  for (let i = 0; i < 3; i++) for (let j = 0; j < 3; j++) o[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  return o;
}
function apply(a, v) { return [0, 1, 2].map((i) => a[3 * i] * v[0] + a[3 * i + 1] * v[1] + a[3 * i + 2] * v[2]); }
function transpose(a) { return [a[0], a[3], a[6], a[1], a[4], a[7], a[2], a[5], a[8]]; }
function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
function cols(a, b, c) { return [a[0], b[0], c[0], a[1], b[1], c[1], a[2], b[2], c[2]]; }
// Rotation about the unit axis by angle radians (Rodrigues).
function turn(ax, angle) {
  const k = [0, -ax[2], ax[1], ax[2], 0, -ax[0], -ax[1], ax[0], 0], k2 = mul(k, k);
  const s = Math.sin(angle), c = 1 - Math.cos(angle);
  return I3.map((v, i) => v + s * k[i] + c * k2[i]);
}

// Quaternion [w, x, y, z] (w >= 0) of a rotation matrix (Shepperd's method, stable near half turns).
function quaternion(m) {
  const tr = m[0] + m[4] + m[8];
  let q;
  if (tr > 0) {
    const s = 2 * Math.sqrt(tr + 1);
    q = [s / 4, (m[7] - m[5]) / s, (m[2] - m[6]) / s, (m[3] - m[1]) / s];
  } else if (m[0] > m[4] && m[0] > m[8]) {
    const s = 2 * Math.sqrt(1 + m[0] - m[4] - m[8]);
    q = [(m[7] - m[5]) / s, s / 4, (m[1] + m[3]) / s, (m[2] + m[6]) / s];
  } else if (m[4] > m[8]) {
    const s = 2 * Math.sqrt(1 + m[4] - m[0] - m[8]);
    q = [(m[2] - m[6]) / s, (m[1] + m[3]) / s, s / 4, (m[5] + m[7]) / s];
  } else {
    const s = 2 * Math.sqrt(1 + m[8] - m[0] - m[4]);
    q = [(m[3] - m[1]) / s, (m[2] + m[6]) / s, (m[5] + m[7]) / s, s / 4];
  }
  return q[0] < 0 ? q.map((v) => -v) : q;
}

// The rotation of quaternion q taken by the share t of its angle (t = 0: none, 1: all of it).
function partTurn(q, t) {
  const half = Math.acos(Math.min(1, q[0])), s = Math.sin(half);
  if (s < 1e-12) return I3.slice();
  return turn([q[1] / s, q[2] / s, q[3] / s], 2 * half * t);
}

// Where each piece sits in the 2D view and in the flat fold: in number order, GAP faces apart, each from
// its own frame, in rows from the top; with `aspect` (the view's width over its height) the rows are as
// wide as makes the faces largest in such a view, else one row. {shift: [[dx, dy] per piece], width,
// height} in faces.
export function pieceOffsets(layout, aspect = 0) {
  const F = layout.faces.length, c = layout.corners, piece = layout.piece || new Array(F).fill(0);
  const pieces = Math.max(...piece) + 1, box = Array.from({length: pieces}, () => [Infinity, Infinity, -Infinity, -Infinity]);
  for (let i = 0; i < F; i++) {
    const b = box[piece[i]];
    for (let k = 0; k < 4; k++) {
      b[0] = Math.min(b[0], c[8 * i + 2 * k]); b[1] = Math.min(b[1], c[8 * i + 2 * k + 1]);
      b[2] = Math.max(b[2], c[8 * i + 2 * k]); b[3] = Math.max(b[3], c[8 * i + 2 * k + 1]);
    }
  }
  const ext = box.map((b) => [b[2] - b[0], b[3] - b[1]]);
  const rows = (most) => { // shelves at most `most` faces wide: each piece's top-left corner (y down), the extent
    let x = 0, y = 0, row = 0, width = 0;
    const at = ext.map(([w, h]) => {
      if (x && x + w > most) { y += row + GAP; x = 0; row = 0; }
      const spot = [x, y];
      width = Math.max(width, x + w); x += w + GAP; row = Math.max(row, h);
      return spot;
    });
    return {at, width, height: y + row};
  };
  let best = rows(Infinity);
  if (aspect > 0) {
    const scale = (r) => Math.min(aspect / r.width, 1 / r.height);
    for (let most = Math.max(...ext.map((e) => e[0])); most < best.width; most++) {
      const r = rows(most);
      if (scale(r) > scale(best)) best = r;
    }
  }
  const shift = box.map((b, q) => [best.at[q][0] - b[0], best.height - best.at[q][1] - ext[q][1] - b[1]]);
  return {shift, width: best.width, height: best.height};
}

// Everything the fold-up needs, computed once per net: each face's pose from the sheet (z = 0) to the
// surface, the order parents come before children, each hinge (point, axis) and its angle.
// The first piece's root stays where it is on the surface, as in voxfab/render/_fold.py; every other
// piece's root moves from beside it in its plane (flat, as the 2D view lays the pieces out) to the
// surface, turning about its centre (`flat`), so that at 0 all the pieces lie flat together.
export function foldPlan(layout, offsets = pieceOffsets(layout).shift) {
  const F = layout.faces.length, c2 = layout.corners, c3 = layout.corners3d;
  const rot = [], shift = [];
  for (let i = 0; i < F; i++) {
    const p = (k) => [c3[12 * i + 3 * k], c3[12 * i + 3 * k + 1], c3[12 * i + 3 * k + 2]];
    const q = (k) => [c2[8 * i + 2 * k], c2[8 * i + 2 * k + 1]];
    const e1 = p(1).map((v, j) => v - p(0)[j]), e3 = p(3).map((v, j) => v - p(0)[j]);
    const d1 = [q(1)[0] - q(0)[0], q(1)[1] - q(0)[1], 0], d3 = [q(3)[0] - q(0)[0], q(3)[1] - q(0)[1], 0];
    // src is orthonormal (a unit square, counter-clockwise), so its inverse is its transpose
    const r = mul(cols(e1, e3, cross(e1, e3)), transpose(cols(d1, d3, [0, 0, 1])));
    const flat0 = apply(r, [q(0)[0], q(0)[1], 0]);
    rot.push(r); shift.push(p(0).map((v, j) => v - flat0[j]));
  }
  const parent = layout.parent, children = Array.from({length: F}, () => []);
  const order = [];
  for (let i = 0; i < F; i++) if (parent[i] >= 0) children[parent[i]].push(i); else order.push(i);
  for (let t = 0; t < order.length; t++) for (const c of children[order[t]]) order.push(c);
  const hinge = new Array(F).fill(null), angle = new Float64Array(F);
  for (const c of order) {
    const p = parent[c];
    if (p < 0) continue;
    const pc = [0, 1, 2, 3].map((k) => [c2[8 * p + 2 * k], c2[8 * p + 2 * k + 1]]);
    const shared = [0, 1, 2, 3].map((k) => [c2[8 * c + 2 * k], c2[8 * c + 2 * k + 1]])
      .filter((a) => pc.some((b) => b[0] === a[0] && b[1] === a[1]));
    let a = [...shared[0], 0], b = [...shared[1], 0];
    let ax = [b[0] - a[0], b[1] - a[1], 0];
    const mid = [0, 1].map((j) => (c2[8 * c + j] + c2[8 * c + 2 + j] + c2[8 * c + 4 + j] + c2[8 * c + 6 + j]) / 4);
    // the child on the axis's left, seen from outside: a positive turn lifts it towards the viewer
    if (ax[0] * (mid[1] - a[1]) - ax[1] * (mid[0] - a[0]) < 0) { a = b; ax = ax.map((v) => -v); }
    const rel = mul(transpose(rot[p]), rot[c]);
    const skew = [(rel[7] - rel[5]) / 2, (rel[2] - rel[6]) / 2, (rel[3] - rel[1]) / 2];
    hinge[c] = {point: a, axis: ax};
    angle[c] = Math.atan2(skew[0] * ax[0] + skew[1] * ax[1] + skew[2] * ax[2], (rel[0] + rel[4] + rel[8] - 1) / 2);
  }
  const piece = layout.piece || new Array(F).fill(0);
  const roots = order.filter((c) => parent[c] < 0), base = roots.find((c) => piece[c] === 0) ?? roots[0];
  const flat = new Array(F).fill(null);
  for (const c of roots) {
    if (c === base) continue;
    const centre = (j) => (c2[8 * c + j] + c2[8 * c + 2 + j] + c2[8 * c + 4 + j] + c2[8 * c + 6 + j]) / 4;
    const cc = [centre(0), centre(1), 0];
    const [ox, oy] = offsets[piece[c]], [bx, by] = offsets[piece[base]];
    const onSheet = apply(rot[base], [cc[0] + ox - bx, cc[1] + oy - by, 0]).map((v, j) => v + shift[base][j]);
    const onSurface = apply(rot[c], cc).map((v, j) => v + shift[c][j]);
    flat[c] = {centre: cc, onSheet, onSurface, turn: quaternion(mul(rot[c], transpose(rot[base]))), start: rot[base]};
  }
  return {F, rot, shift, order, hinge, angle, parent, c2, flat};
}

// Face corners (F*12 numbers) at fold fraction t: 0 flat (every piece in the plane of the first piece's
// root, laid out as in the 2D view), 1 the surface.
// Flat typed arrays and inlined 3×3 products: this runs once per animation frame over every face.
export function foldCorners(plan, t) {
  const {F, rot, shift, order, hinge, angle, parent, c2, flat} = plan;
  const R = new Float64Array(9 * F), S = new Float64Array(3 * F), out = new Float64Array(12 * F);
  for (const c of order) {
    const p = parent[c], rc = 9 * c, sc = 3 * c;
    if (p < 0 && flat[c]) {
      // a piece's root on its way from flat beside the first piece to the surface
      const f = flat[c], r = mul(partTurn(f.turn, t), f.start), mid = apply(r, f.centre);
      for (let m = 0; m < 9; m++) R[rc + m] = r[m];
      for (let m = 0; m < 3; m++) S[sc + m] = (1 - t) * f.onSheet[m] + t * f.onSurface[m] - mid[m];
    } else if (p < 0) {
      for (let m = 0; m < 9; m++) R[rc + m] = rot[c][m];
      for (let m = 0; m < 3; m++) S[sc + m] = shift[c][m];
    } else {
      const {point, axis} = hinge[c], tn = turn(axis, t * angle[c]), rp = 9 * p, sp = 3 * p;
      // d = point - turn·point (point has z = 0)
      const d0 = point[0] - (tn[0] * point[0] + tn[1] * point[1]);
      const d1 = point[1] - (tn[3] * point[0] + tn[4] * point[1]);
      const d2 = -(tn[6] * point[0] + tn[7] * point[1]);
      for (let i = 0; i < 3; i++) {
        const a0 = R[rp + 3 * i], a1 = R[rp + 3 * i + 1], a2 = R[rp + 3 * i + 2];
        for (let j = 0; j < 3; j++) R[rc + 3 * i + j] = a0 * tn[j] + a1 * tn[3 + j] + a2 * tn[6 + j];
        S[sc + i] = a0 * d0 + a1 * d1 + a2 * d2 + S[sp + i];
      }
    }
    for (let k = 0; k < 4; k++) {
      const x = c2[8 * c + 2 * k], y = c2[8 * c + 2 * k + 1];
      for (let j = 0; j < 3; j++) out[12 * c + 3 * k + j] = R[rc + 3 * j] * x + R[rc + 3 * j + 1] * y + S[sc + j];
    }
  }
  return out;
}

function pairKey(i, j) { return i < j ? `${i}-${j}` : `${j}-${i}`; }

// {lo, hi}: the box of 3D corners (x, y, z in a row).
function bounds3d(c) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < c.length; i += 3) {
    for (let j = 0; j < 3; j++) { lo[j] = Math.min(lo[j], c[i + j]); hi[j] = Math.max(hi[j], c[i + j]); }
  }
  return {lo, hi};
}

export class NetView {
  // canvas: the net-2d canvas; viewer: the 3D Viewer; shape(): the current Grid; say(text, ok): status;
  // onChange(): the marks changed.
  // pieces: the box of the buttons that show the whole net or one piece of it, fitted.
  constructor(canvas, {viewer, shape, say, onChange, fold = null, play = null, undo = null, pieces = null, placement = null}) {
    Object.assign(this, {canvas, viewer, shape, say, onChange, foldInput: fold, playButton: play, piecesBox: pieces,
      shownPlacement: placement});
    this.layout = null; this.job = null; this.index = 0; this.marks = {cut: [], keep: []};
    this.view = null; this.hover = null; this.busy = false; this.version = 0; this.undos = 0;
    this._drag = null;
    canvas.addEventListener('wheel', (e) => {
      if (!this.view) return;
      e.preventDefault();
      const [px, py] = this._pixel(e), f = Math.exp(-e.deltaY * 0.0015);
      const v = this.view, s = Math.max(v.fit * 0.5, Math.min(v.fit * 40, v.s * f)), k = s / v.s;
      // zoom about the pointer: the net point under it stays under it
      v.ox = px - (px - v.ox) * k; v.oy = py - (py - v.oy) * k; v.s = s;
      this.draw();
    }, {passive: false});
    canvas.addEventListener('pointerdown', (e) => {
      this._drag = {at: this._pixel(e), moved: 0}; canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener('pointermove', (e) => {
      const p = this._pixel(e);
      if (this._drag && this.view) {
        const [x0, y0] = this._drag.at;
        this._drag.moved += Math.abs(p[0] - x0) + Math.abs(p[1] - y0);
        this._drag.at = p;
        if (this._drag.moved > 4) { this.view.ox += p[0] - x0; this.view.oy += p[1] - y0; canvas.style.cursor = 'grabbing'; this.draw(); }
        return;
      }
      this.setHover(this.hit(...p), true);
    });
    canvas.addEventListener('pointerup', (e) => {
      const d = this._drag; this._drag = null; canvas.style.cursor = '';
      if (d && d.moved <= 4) {
        const h = this.hit(...this._pixel(e));
        if (h && h.k !== null) this.edit(h.i, h.k);
      }
    });
    canvas.addEventListener('pointerleave', () => { if (!this._drag) this.setHover(null, true); });
    if (viewer) {
      viewer.onPick = (hit, clicked) => {
        const h = this._fromViewer(hit);
        this.setHover(h, false);
        if (clicked && h && h.k !== null) this.edit(h.i, h.k);
      };
    }
    if (fold) fold.addEventListener('input', () => this.fold(Number(fold.value) / 100));
    if (play) play.addEventListener('click', () => this.play());
    if (undo) undo.addEventListener('click', () => this.undo());
    window.voxfabFold = (t = 1) => this.foldState(t);
    window.voxfabNetView = this; // for scripts driving the page: toScreen, layout, hit
    // The canvas takes the size its column shows it at, in its own pixels (see resize).
    new ResizeObserver(() => this.resize()).observe(canvas);
    window.addEventListener('resize', () => this.resize());
  }

  // As wide as the column shows the canvas, and as tall as the window leaves room for: a face is as big as
  // it can be. The net is fitted again to the new size.
  resize() {
    const c = this.canvas, w = Math.round(c.clientWidth);
    if (!w) return; // hidden (another tab)
    const h = Math.round(Math.max(280, Math.min(1.25 * w, window.innerHeight - ROOM_BELOW)));
    if (c.width === w && c.height === h) return;
    c.width = w; c.height = h;
    if (this.layout) this.setNet(this.job, this.index, this.layout); else this.draw();
  }

  _pixel(e) {
    const r = this.canvas.getBoundingClientRect();
    return [(e.clientX - r.left) * this.canvas.width / r.width, (e.clientY - r.top) * this.canvas.height / r.height];
  }

  // Compatibility with the gallery code: a null layout clears the view.
  setLayout(layout) { if (!layout) this.setNet(null, 0, null); else this.setNet(this.job, this.index, layout); }

  setNet(job, index, layout, {keepView = false} = {}) {
    this.job = job; this.index = index; this.layout = layout; this.hover = null; this._plan = null;
    // what was lit belongs to the net before: the 3D view lets it go too (a pointer still over an
    // edge lights it again on its next move)
    if (this.viewer) {
      this.viewer.setHighlight(null);
      if (!layout && this.viewer.quads) this.viewer.setQuads(null);
    }
    this.version += 1;
    const ds = this.canvas.dataset;
    ds.version = String(this.version); ds.job = job || ''; ds.faces = layout ? String(layout.faces.length) : '0';
    if (!layout) { this.view = null; this.pieceButtons(0); this.draw(); return; }
    const F = layout.faces.length, c = layout.corners, piece = layout.piece || new Array(F).fill(0);
    // pieces in rows shaped as the canvas is, each in its own frame
    const W = this.canvas.width, H = this.canvas.height;
    const {shift, width: w, height: h} = pieceOffsets(layout, W / H);
    this.shift = shift;
    this.pts = new Float64Array(8 * F);
    this.cells = new Map(); this.names = new Map(); this.foldsSet = new Set();
    for (let i = 0; i < F; i++) {
      const [sx, sy] = this.shift[piece[i]];
      let mx = Infinity, my = Infinity;
      for (let k = 0; k < 4; k++) {
        this.pts[8 * i + 2 * k] = c[8 * i + 2 * k] + sx; this.pts[8 * i + 2 * k + 1] = c[8 * i + 2 * k + 1] + sy;
        mx = Math.min(mx, this.pts[8 * i + 2 * k]); my = Math.min(my, this.pts[8 * i + 2 * k + 1]);
      }
      this.cells.set(`${mx},${my}`, i);
      this.names.set(faceName(layout.faces[i]), i);
    }
    for (let t = 0; t < layout.folds.length; t += 2) this.foldsSet.add(pairKey(layout.folds[t], layout.folds[t + 1]));
    // a painted shape's faces in their voxels' colours, here and folding up in the 3D view
    this.colours = faceColours(layout, this.shape && this.shape());
    this.fills = this.colours && this.colours.map((c) => c && `rgb(${c[0]},${c[1]},${c[2]})`);
    const fit = Math.min((W - 16) / w, (H - 16) / h), pieces = Math.max(...piece) + 1;
    this.pieceButtons(pieces);
    if (!keepView || !this.view) {
      this.view = {s: fit, fit, ox: (W - fit * w) / 2, oy: H - (H - fit * h) / 2};
      // zoomed to fit what can be worked on: the whole net, or its first piece when the whole is too small to click
      if (fit * this._cssPerPixel() < MIN_FACE_PX && pieces > 1) this.fitTo(0, false);
      else this.fitted(null);
    }
    this.draw();
    if (this.foldInput && Number(this.foldInput.value) > 0) this.fold(Number(this.foldInput.value) / 100);
  }

  // The buttons "whole net", "piece 1", ... of a net in pieces (none for a net in one piece).
  pieceButtons(pieces) {
    const box = this.piecesBox;
    if (!box || Number(box.dataset.pieces || 0) === pieces) return;
    box.dataset.pieces = String(pieces);
    const button = (text, q) => {
      const b = Object.assign(document.createElement('button'), {type: 'button', textContent: text});
      b.dataset.piece = q === null ? 'all' : String(q + 1);
      b.addEventListener('click', () => this.fitTo(q));
      return b;
    };
    box.replaceChildren(...(pieces > 1 ? [button('whole net', null), ...Array.from({length: pieces}, (_, q) => button(`piece ${q + 1}`, q))] : []));
  }

  // Fit the view to piece q (null: the whole net), centred.
  fitTo(q, redraw = true) {
    if (!this.layout) return;
    const P = this.pts, F = this.layout.faces.length, piece = this.layout.piece || new Array(F).fill(0);
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (let i = 0; i < F; i++) {
      if (q !== null && piece[i] !== q) continue;
      for (let k = 8 * i; k < 8 * i + 8; k += 2) {
        x0 = Math.min(x0, P[k]); x1 = Math.max(x1, P[k]); y0 = Math.min(y0, P[k + 1]); y1 = Math.max(y1, P[k + 1]);
      }
    }
    const W = this.canvas.width, H = this.canvas.height;
    let s = Math.min((W - 16) / (x1 - x0), (H - 16) / (y1 - y0));
    if (q !== null) s = Math.min(s, MAX_FACE_PX / this._cssPerPixel());
    Object.assign(this.view, {s, ox: (W - s * (x1 - x0)) / 2 - x0 * s, oy: H - (H - s * (y1 - y0)) / 2 + y0 * s});
    this.fitted(q);
    if (redraw) this.draw();
  }

  // Screen px per canvas pixel (1 while the canvas is hidden: resize() keeps the two alike).
  _cssPerPixel() { return (this.canvas.getBoundingClientRect().width || this.canvas.width) / this.canvas.width; }

  fitted(q) {
    const name = q === null ? 'all' : String(q + 1);
    this.canvas.dataset.fitted = name;
    if (this.piecesBox) for (const b of this.piecesBox.children) b.classList.toggle('active', b.dataset.piece === name);
  }

  toScreen(x, y) { const v = this.view; return [v.ox + x * v.s, v.oy - y * v.s]; }
  toNet(px, py) { const v = this.view; return [(px - v.ox) / v.s, (v.oy - py) / v.s]; }

  // {i, k}: the face under the pixel and its edge k when the pixel is within a quarter face of it.
  hit(px, py) {
    if (!this.layout || !this.view) return null;
    const [x, y] = this.toNet(px, py), cx = Math.floor(x), cy = Math.floor(y);
    const i = this.cells.get(`${cx},${cy}`);
    if (i === undefined) return null;
    const P = this.pts;
    let best = null, bestD = 0.25;
    for (let k = 0; k < 4; k++) {
      const ax = P[8 * i + 2 * k], ay = P[8 * i + 2 * k + 1], bx = P[8 * i + 2 * ((k + 1) % 4)], by = P[8 * i + 2 * ((k + 1) % 4) + 1];
      const d = ax === bx ? Math.abs(x - ax) : Math.abs(y - ay);
      if (d < bestD) { bestD = d; best = k; }
    }
    return {i, k: best};
  }

  // The other half of edge k of face i: {j, k2} (the same edge in 3D, on the face across it).
  partner(i, k) {
    const L = this.layout, j = L.neighbor[4 * i + k], c3 = L.corners3d;
    const p = edgeKey(c3.slice(12 * i + 3 * k, 12 * i + 3 * k + 3), c3.slice(12 * i + 3 * ((k + 1) % 4), 12 * i + 3 * ((k + 1) % 4) + 3));
    for (let m = 0; m < 4; m++) {
      if (L.neighbor[4 * j + m] !== i) continue;
      const q = edgeKey(c3.slice(12 * j + 3 * m, 12 * j + 3 * m + 3), c3.slice(12 * j + 3 * ((m + 1) % 4), 12 * j + 3 * ((m + 1) % 4) + 3));
      if (q === p) return {j, k2: m};
    }
    return {j, k2: null};
  }

  _edge3d(i, k) {
    const c3 = this.layout.corners3d;
    return [Array.from(c3.slice(12 * i + 3 * k, 12 * i + 3 * k + 3)), Array.from(c3.slice(12 * i + 3 * ((k + 1) % 4), 12 * i + 3 * ((k + 1) % 4) + 3))];
  }

  label(i, j) { return (this.layout.labels || {})[pairKey(i, j)] || null; }

  _fromViewer(hit) {
    if (!hit || !this.layout) return null;
    const i = this.names.get(hit.face);
    if (i === undefined) return null;
    let k = null;
    if (hit.edge) {
      const want = edgeKey(hit.edge[0], hit.edge[1]);
      for (let m = 0; m < 4; m++) { const [p, q] = this._edge3d(i, m); if (edgeKey(p, q) === want) k = m; }
    }
    return {i, k};
  }

  // Light up a face or an edge here and in the 3D view (toViewer: the hover started here).
  setHover(h, toViewer) {
    const same = (a, b) => (a === b) || (a && b && a.i === b.i && a.k === b.k);
    if (same(h, this.hover)) return;
    this.hover = h;
    const ds = this.canvas.dataset;
    if (h) {
      ds.hoverFace = faceName(this.layout.faces[h.i]);
      ds.hoverEdge = h.k === null ? '' : String(h.k);
      if (h.k !== null) { const {j} = this.partner(h.i, h.k); ds.hoverLabel = this.label(h.i, j) || ''; } else ds.hoverLabel = '';
    } else { delete ds.hoverFace; delete ds.hoverEdge; delete ds.hoverLabel; }
    this.draw();
    if (!this.viewer) return;
    if (!h) { this.viewer.setHighlight(null); return; }
    const faces = new Set([faceName(this.layout.faces[h.i])]);
    let edges = [], label = null;
    if (h.k !== null) {
      const {j} = this.partner(h.i, h.k);
      faces.add(faceName(this.layout.faces[j]));
      edges = [this._edge3d(h.i, h.k)];
      label = this.label(h.i, j);
    }
    this.viewer.setHighlight({faces, edges, label});
    if (!toViewer) return;
  }

  draw() {
    const {canvas} = this, ctx = canvas.getContext('2d'), W = canvas.width, H = canvas.height;
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, W, H);
    if (!this.layout) return;
    const L = this.layout, P = this.pts, F = L.faces.length, s = this.view.s;
    const corner = (i, k) => this.toScreen(P[8 * i + 2 * (k % 4)], P[8 * i + 2 * (k % 4) + 1]);
    const faces = new Path2D();
    for (let i = 0; i < F; i++) {
      if (this.fills && this.fills[i]) { // a painted face on its own
        ctx.beginPath(); ctx.moveTo(...corner(i, 0)); for (let k = 1; k < 4; k++) ctx.lineTo(...corner(i, k));
        ctx.closePath(); ctx.fillStyle = this.fills[i]; ctx.fill();
        continue;
      }
      faces.moveTo(...corner(i, 0)); for (let k = 1; k < 4; k++) faces.lineTo(...corner(i, k)); faces.closePath();
    }
    ctx.fillStyle = '#fbf1e2'; ctx.fill(faces);
    const lw = Math.max(0.6, Math.min(2.5, s / 8)), cuts = new Path2D();
    const byType = {1: new Path2D(), '-1': new Path2D(), 0: new Path2D()};
    for (let i = 0; i < F; i++) {
      for (let k = 0; k < 4; k++) {
        const j = L.neighbor[4 * i + k];
        if (this.foldsSet.has(pairKey(i, j))) {
          if (i > j) continue;
          const path = byType[L.fold_type[4 * i + k]] || byType[0];
          path.moveTo(...corner(i, k)); path.lineTo(...corner(i, k + 1));
        } else { cuts.moveTo(...corner(i, k)); cuts.lineTo(...corner(i, k + 1)); }
      }
    }
    if (this.fills) { // on painted faces, cuts and folds over a white line: a red cut on a red face still shows
      ctx.setLineDash([]); ctx.strokeStyle = '#fff'; ctx.lineWidth = lw * 2;
      for (const path of [byType[1], byType[-1], cuts]) ctx.stroke(path);
    }
    for (const [type, path] of Object.entries(byType)) {
      const st = FOLD_STYLE[type];
      ctx.strokeStyle = st.color; ctx.lineWidth = lw * 0.8; ctx.setLineDash(s > 8 ? st.dash : []); ctx.stroke(path);
    }
    ctx.setLineDash([]); ctx.strokeStyle = '#ff0000'; ctx.lineWidth = lw; ctx.stroke(cuts);
    const h = this.hover;
    if (!h) return;
    ctx.save();
    ctx.beginPath(); ctx.moveTo(...corner(h.i, 0)); for (let k = 1; k < 4; k++) ctx.lineTo(...corner(h.i, k)); ctx.closePath();
    ctx.fillStyle = 'rgba(255, 150, 30, 0.55)'; ctx.fill();
    if (h.k !== null) {
      const {j, k2} = this.partner(h.i, h.k), label = this.label(h.i, j);
      ctx.lineCap = 'round'; ctx.strokeStyle = '#d0006f'; ctx.lineWidth = Math.max(3, lw * 2.5);
      const halves = [[h.i, h.k]];
      if (k2 !== null) halves.push([j, k2]);
      ctx.font = 'bold 13px sans-serif'; ctx.fillStyle = '#d0006f';
      for (const [f, k] of halves) {
        const a = corner(f, k), b = corner(f, k + 1);
        ctx.beginPath(); ctx.moveTo(...a); ctx.lineTo(...b); ctx.stroke();
        if (label && !this.foldsSet.has(pairKey(h.i, j))) ctx.fillText(label, (a[0] + b[0]) / 2 + 5, (a[1] + b[1]) / 2 - 5);
      }
    }
    ctx.restore();
  }

  // Cut the fold or join the seam at edge k of face i; the server repairs the net around it.
  async edit(i, k) {
    if (this.busy || !this.job) return;
    const L = this.layout, j = L.neighbor[4 * i + k];
    const kind = this.foldsSet.has(pairKey(i, j)) ? 'cut' : 'join';
    // with pieces allowed (the Net tab's pieces choice), a cut leaves the cut-off side as a piece
    const pieces = document.querySelector('[data-testid="net-pieces"]');
    const split = kind === 'cut' && pieces && pieces.value === 'auto' ? {split: true} : {};
    await this._send({[kind]: [L.faces[i], L.faces[j]], ...split}, kind);
  }

  async undo() {
    if (this.job && this.undos > 0) await this._send({undo: true}, 'undo');
    else if (this.say) this.say(this.job ? 'Nothing to undo: this net has no edit left to take back.' : 'Nothing to undo: choose a net first.', true);
  }

  async _send(change, kind) {
    this.busy = true;
    this.canvas.dataset.busy = '1'; // the page waits for the server's answer: clicks meanwhile are ignored
    const t0 = performance.now();
    try {
      const shape = this.shape && this.shape();
      // the pieces as the sheets show them (moved by hand perhaps): those the edit leaves alone stay there
      const placement = this.shownPlacement ? this.shownPlacement() : null;
      const r = await post('/api/nets/edit', {job: this.job, index: this.index, ...change, grid: shape ? shape.pack() : null,
        marks: this.marks, ...(placement ? {placement} : {})});
      const ms = performance.now() - t0;
      this.marks = r.net.marks; this.undos = r.net.undo;
      this.item = {...r.net, job: r.job}; // the edited net: its layout, fit and placement on the sheets
      this.setNet(r.job, 0, r.net.layout, {keepView: true});
      const ds = this.canvas.dataset;
      ds.edit = kind; ds.moved = String(r.net.moved); ds.seconds = String(r.net.seconds); ds.ms = ms.toFixed(0);
      const words = {cut: 'Cut', join: 'Joined', undo: 'Undid the last edit'}[kind];
      if (this.say) this.say(kind === 'undo' ? `${words}.` : `${words} the edge: ${r.net.moved} face(s) moved, laid out in ${(ms / 1000).toFixed(2)} s.`, true);
      if (this.onChange) this.onChange();
    } catch (e) {
      if (this.say) this.say(e.message);
      this.canvas.dataset.error = e.message;
    } finally { this.busy = false; delete this.canvas.dataset.busy; }
  }

  clear() { this.marks = {cut: [], keep: []}; this.draw(); if (this.onChange) this.onChange(); }

  // The marks so far, for regenerating the gallery with them.
  constraints() { return {cut: this.marks.cut.slice(), keep: this.marks.keep.slice()}; }

  // Fold-up at t in [0, 1] in the 3D view.
  // the flat fold lays the pieces out as the 2D view does
  _planned() { if (!this._plan && this.layout) this._plan = foldPlan(this.layout, this.shift); return this._plan; }

  fold(t) {
    const plan = this._planned();
    if (!plan || !this.viewer) return null;
    const t0 = performance.now();
    const corners = foldCorners(plan, t);
    // Framed on the net as it is at t: folded, the shape fills the view (framed on the flat net too, it
    // came out small and off centre); the bounds move smoothly with t, so the animation does not jump.
    this.viewer.setQuads(corners, bounds3d(corners), this.layout.faces.map(faceName), this.colours);
    const ms = performance.now() - t0;
    this.canvas.dataset.foldMs = ms.toFixed(1);
    return ms;
  }

  play(seconds = 3) {
    if (!this._planned()) return;
    const start = performance.now(), times = [];
    const step = () => {
      const t = Math.min(1, (performance.now() - start) / (1000 * seconds));
      if (this.foldInput) this.foldInput.value = String(Math.round(100 * t));
      times.push(this.fold(t));
      if (t < 1) requestAnimationFrame(step);
      else this.canvas.dataset.foldFrameMs = (times.reduce((a, b) => a + b, 0) / times.length).toFixed(1);
    };
    requestAnimationFrame(step);
  }

  // For tests: the folded corners at t and the surface's own corners (layout corners3d).
  foldState(t = 1) {
    const plan = this._planned();
    if (!plan) return null;
    return {corners: Array.from(foldCorners(plan, t)), corners3d: this.layout.corners3d.slice(), faces: this.layout.faces.length};
  }
}
