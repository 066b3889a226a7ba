// A small voxel viewer on a 2D canvas: orthographic orbit camera, painter's order, shaded faces
// with dark voxel edges. Drag to orbit, wheel to zoom. No WebGL needed, so it runs anywhere.
// It also shows a net folding up (setQuads), and lights up the faces and seam edges the net view
// points at (setHighlight); hovering or clicking a face or edge here tells the net view (onPick).

import {DIRS, exposedFaces} from './grid.js';

const LIGHT = normalize([0.45, 0.3, 0.85]);
// A weaker fill light from the other side, so faces turned away from the key light are not black.
const FILL = normalize([-0.6, -0.45, 0.25]);
const NAMES = ['+x', '-x', '+y', '-y', '+z', '-z'];

// Brightness of a face of unit normal n seen from `eye`: ambient, key and fill light, a touch of
// facing. Every face the camera sees gets at least the ambient 0.62, whatever its direction.
export function shade(n, eye) {
  return Math.min(1.08, 0.62 + 0.3 * Math.max(0, dot(n, LIGHT)) + 0.14 * Math.max(0, dot(n, FILL))
    + 0.06 * Math.max(0, dot(n, eye)));
}

// "x,y,z,+z": a face's name, as the net layout's faces name it.
export function faceName(f) { return `${f[0]},${f[1]},${f[2]},${typeof f[3] === 'number' ? NAMES[f[3]] : f[3]}`; }
function pointKey(p) { return `${p[0]},${p[1]},${p[2]}`; }
export function edgeKey(p, q) { const a = pointKey(p), b = pointKey(q); return a < b ? `${a}|${b}` : `${b}|${a}`; }

function normalize(v) { const l = Math.hypot(...v) || 1; return v.map((c) => c / l); }
function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
function hexRgb(h) { return [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16)); }

export class Viewer {
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.yaw = -0.8; this.pitch = 0.55; this.zoom = 1.0;
    this.grid = null; this.faces = []; this.layer = null; this.version = 0; this.mesh = null;
    this.color = hexRgb('#eccc96'); this.accent = hexRgb('#e07b39');
    this.frames = null; this.timer = null;
    this._drag = null;
    this.quads = null; // folding net: {corners: Float64Array(F*12), normalsFlip, lo, hi}
    this.highlight = null; // {faces: Set of face names, edges: [[p, q]], label}
    this.onPick = null; // (hit, clicked) with hit {face: name, edge: [p, q]} or null
    this._polys = [];
    canvas.addEventListener('pointerdown', (e) => {
      this._drag = [e.clientX, e.clientY]; this._moved = 0;
      canvas.setPointerCapture(e.pointerId); canvas.style.cursor = 'grabbing';
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!this._drag) { this._hover(e, false); return; }
      const [x0, y0] = this._drag; this._drag = [e.clientX, e.clientY];
      this._moved += Math.abs(e.clientX - x0) + Math.abs(e.clientY - y0);
      this.yaw -= (e.clientX - x0) * 0.01;
      this.pitch = Math.max(-1.5, Math.min(1.5, this.pitch + (e.clientY - y0) * 0.01));
      this.draw();
    });
    const end = () => { this._drag = null; canvas.style.cursor = 'grab'; };
    canvas.addEventListener('pointerup', (e) => { if (this._drag && this._moved < 4) this._hover(e, true); end(); });
    canvas.addEventListener('pointercancel', end);
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.zoom = Math.max(0.3, Math.min(6, this.zoom * Math.exp(-e.deltaY * 0.0015)));
      this.draw();
    }, {passive: false});
  }

  // Show a grid; `layer` (a z index or null) is highlighted for the editor.
  setGrid(grid, layer = this.layer) {
    this.grid = grid; this.layer = layer; this.mesh = null; this.quads = null;
    // a lit face or seam belongs to a net of the shape shown before
    this.highlight = null; this.canvas.dataset.highlight = ''; this.canvas.dataset.highlightLabel = '';
    this.faces = exposedFaces(grid);
    this.version += 1;
    this.canvas.dataset.version = String(this.version);
    this.canvas.dataset.faces = String(this.faces.length);
    this.draw();
  }

  setLayer(layer) { this.layer = layer; this.draw(); }

  // Light up faces (names "x,y,z,+z") and seam edges ([p, q] 3D points), with a label; null clears.
  setHighlight(h) {
    this.highlight = h;
    this.canvas.dataset.highlight = h ? [...h.faces].sort().join(' ') : '';
    this.canvas.dataset.highlightLabel = h && h.label ? h.label : '';
    this.draw();
  }

  // Show a net folding: `corners` F*12 numbers (4 corners per face in 3D), framed by `frame` ({lo, hi}: the
  // box fitted in the view, centred); null goes back to the shape.
  setQuads(corners, frame = null, names = null) {
    this.quads = corners ? {corners, frame: frame || this.quads?.frame, names} : null;
    this.draw();
  }

  _hover(e, clicked) {
    if (!this.onPick) return;
    const r = this.canvas.getBoundingClientRect();
    const px = (e.clientX - r.left) * this.canvas.width / r.width, py = (e.clientY - r.top) * this.canvas.height / r.height;
    this.onPick(this.pick(px, py), clicked);
  }

  // The face under a canvas pixel (the nearest one drawn there) and its nearest edge, or null.
  pick(px, py) {
    for (let t = this._polys.length - 1; t >= 0; t--) {
      const {name, pts, p3} = this._polys[t];
      let inside = true, sign = 0;
      for (let k = 0; k < 4 && inside; k++) {
        const a = pts[k], b = pts[(k + 1) % 4];
        const c = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
        if (c !== 0) { if (sign && Math.sign(c) !== sign) inside = false; sign = Math.sign(c); }
      }
      if (!inside) continue;
      let best = 0, bestD = Infinity;
      for (let k = 0; k < 4; k++) {
        const a = pts[k], b = pts[(k + 1) % 4];
        const l2 = (b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2 || 1;
        const u = Math.max(0, Math.min(1, ((px - a[0]) * (b[0] - a[0]) + (py - a[1]) * (b[1] - a[1])) / l2));
        const d = Math.hypot(px - a[0] - u * (b[0] - a[0]), py - a[1] - u * (b[1] - a[1]));
        if (d < bestD) { bestD = d; best = k; }
      }
      const side = Math.hypot(pts[1][0] - pts[0][0], pts[1][1] - pts[0][1]);
      return {face: name, edge: bestD < Math.max(3, side * 0.25) ? [p3[best], p3[(best + 1) % 4]] : null};
    }
    return null;
  }

  // Faces and seam edges of the highlight, over what draw() painted.
  _drawHighlight(project) {
    const h = this.highlight;
    if (!h) return;
    const {ctx} = this;
    ctx.save();
    for (const {name, pts} of this._polys) {
      if (!h.faces || !h.faces.has(name)) continue;
      ctx.beginPath(); ctx.moveTo(...pts[0]); for (let k = 1; k < 4; k++) ctx.lineTo(...pts[k]); ctx.closePath();
      ctx.fillStyle = 'rgba(255, 150, 30, 0.6)'; ctx.fill();
    }
    ctx.lineCap = 'round'; ctx.strokeStyle = '#d0006f'; ctx.lineWidth = 4;
    for (const [p, q] of h.edges || []) {
      const a = project(p), b = project(q);
      ctx.beginPath(); ctx.moveTo(...a); ctx.lineTo(...b); ctx.stroke();
    }
    if (h.label && h.edges && h.edges.length) {
      const [p, q] = h.edges[0], a = project(p), b = project(q);
      ctx.font = 'bold 14px sans-serif'; ctx.fillStyle = '#d0006f'; ctx.strokeStyle = '#fff'; ctx.lineWidth = 3;
      ctx.strokeText(h.label, (a[0] + b[0]) / 2 + 6, (a[1] + b[1]) / 2 - 6);
      ctx.fillText(h.label, (a[0] + b[0]) / 2 + 6, (a[1] + b[1]) / 2 - 6);
    }
    ctx.restore();
  }

  // The folding net: painter's order, the outside shaded as the shape, the back paper-grey.
  _drawQuads(eye, right, up) {
    const {canvas, ctx} = this;
    const W = canvas.width, H = canvas.height;
    const {corners, frame, names} = this.quads;
    const lo = frame ? frame.lo : [0, 0, 0], hi = frame ? frame.hi : [25, 25, 25];
    const c = [0, 1, 2].map((j) => (lo[j] + hi[j]) / 2);
    const scale = this.zoom * 0.95 * Math.min(W, H) / (Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1);
    const project = (p) => {
      const q = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
      return [W / 2 + scale * dot(q, right), H / 2 - scale * dot(q, up)];
    };
    const F = corners.length / 12, depth = new Float64Array(F), order = new Uint32Array(F);
    for (let i = 0; i < F; i++) {
      let d = 0;
      for (let k = 0; k < 4; k++) {
        const o = 12 * i + 3 * k;
        d += (corners[o] - c[0]) * eye[0] + (corners[o + 1] - c[1]) * eye[1] + (corners[o + 2] - c[2]) * eye[2];
      }
      depth[i] = d; order[i] = i;
    }
    order.sort((a, b) => depth[a] - depth[b]);
    this._polys = [];
    // colours by brightness step, made once: a CSS colour string per face is most of a frame's cost
    const colours = new Map();
    const colour = (front, light) => {
      const key = (front ? 1000 : 0) + Math.round(light * 200);
      let hit = colours.get(key);
      if (!hit) {
        const base = front ? this.color : [205, 205, 205], l = Math.round(light * 200) / 200;
        const rgb = base.map((v) => Math.min(255, Math.round(v * l)));
        hit = [`rgb(${rgb[0]},${rgb[1]},${rgb[2]})`, `rgb(${rgb[0] * 0.7 | 0},${rgb[1] * 0.7 | 0},${rgb[2] * 0.7 | 0})`];
        colours.set(key, hit);
      }
      return hit;
    };
    const edges = scale >= 6; // face edges only where faces are big enough to show them
    ctx.lineJoin = 'round'; ctx.lineWidth = Math.max(0.3, Math.min(1, scale / 25));
    for (const i of order) {
      const o = 12 * i;
      const e1 = [corners[o + 3] - corners[o], corners[o + 4] - corners[o + 1], corners[o + 5] - corners[o + 2]];
      const e3 = [corners[o + 9] - corners[o], corners[o + 10] - corners[o + 1], corners[o + 11] - corners[o + 2]];
      const n = normalize([e1[1] * e3[2] - e1[2] * e3[1], e1[2] * e3[0] - e1[0] * e3[2], e1[0] * e3[1] - e1[1] * e3[0]]);
      const front = dot(n, eye) > 0;
      const [fill, line] = colour(front, shade(front ? n : [-n[0], -n[1], -n[2]], eye));
      const pts = [];
      for (let k = 0; k < 4; k++) {
        const q = [corners[o + 3 * k] - c[0], corners[o + 3 * k + 1] - c[1], corners[o + 3 * k + 2] - c[2]];
        pts.push([W / 2 + scale * dot(q, right), H / 2 - scale * dot(q, up)]);
      }
      ctx.beginPath(); ctx.moveTo(pts[0][0], pts[0][1]);
      for (let k = 1; k < 4; k++) ctx.lineTo(pts[k][0], pts[k][1]);
      ctx.closePath(); ctx.fillStyle = fill; ctx.fill();
      if (edges) { ctx.strokeStyle = line; ctx.stroke(); }
      if (front && names) {
        const p3 = [0, 1, 2, 3].map((k) => [corners[o + 3 * k], corners[o + 3 * k + 1], corners[o + 3 * k + 2]]);
        this._polys.push({name: names[i], pts, p3});
      }
    }
    this._drawHighlight(project);
  }

  // Show triangles in mm instead of the grid: the plates of a construction as assembled.
  // `plates` is [{name, triangles: [x0, y0, z0, x1, ...]}]; each plate gets its own tint.
  setMesh(plates) {
    const tris = [];
    let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    plates.forEach((p, k) => {
      const t = p.triangles;
      for (let i = 0; i + 8 < t.length; i += 9) {
        const a = [t[i], t[i + 1], t[i + 2]], b = [t[i + 3], t[i + 4], t[i + 5]], c = [t[i + 6], t[i + 7], t[i + 8]];
        for (const q of [a, b, c]) for (let j = 0; j < 3; j++) { lo[j] = Math.min(lo[j], q[j]); hi[j] = Math.max(hi[j], q[j]); }
        const u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]], v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        const n = normalize([u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]);
        tris.push({pts: [a, b, c], n, plate: k});
      }
    });
    this.mesh = {tris, lo, hi, count: plates.length};
    this.version += 1;
    this.canvas.dataset.version = String(this.version);
    this.canvas.dataset.plates = String(plates.length);
    this.draw();
  }

  _drawMesh(eye, right, up) {
    const {canvas, ctx} = this;
    const W = canvas.width, H = canvas.height;
    const {tris, lo, hi} = this.mesh;
    this._polys = []; // the plates are not faces of the net: nothing to pick
    const c = [0, 1, 2].map((j) => (lo[j] + hi[j]) / 2);
    const scale = this.zoom * 0.95 * Math.min(W, H) / (Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1);
    const project = (p) => {
      const q = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
      return [W / 2 + scale * dot(q, right), H / 2 - scale * dot(q, up)];
    };
    const depth = (t) => dot([(t.pts[0][0] + t.pts[1][0] + t.pts[2][0]) / 3 - c[0],
      (t.pts[0][1] + t.pts[1][1] + t.pts[2][1]) / 3 - c[1], (t.pts[0][2] + t.pts[1][2] + t.pts[2][2]) / 3 - c[2]], eye);
    const order = tris.map((t) => [depth(t), t]).sort((a, b) => a[0] - b[0]);
    for (const [, t] of order) {
      const pts = t.pts.map(project);
      const light = shade(dot(t.n, eye) >= 0 ? t.n : t.n.map((v) => -v), eye);
      const tint = t.plate % 2 ? this.color : [214, 180, 120];
      const rgb = tint.map((v) => Math.min(255, Math.round(v * light)));
      ctx.beginPath(); ctx.moveTo(...pts[0]); ctx.lineTo(...pts[1]); ctx.lineTo(...pts[2]); ctx.closePath();
      ctx.fillStyle = ctx.strokeStyle = `rgb(${rgb[0]},${rgb[1]},${rgb[2]})`;
      ctx.fill(); ctx.lineWidth = 0.5; ctx.stroke();
    }
  }

  play(frames, fps = 10) {
    this.stop();
    this.frames = frames; let i = 0;
    this.timer = setInterval(() => { this.setGrid(frames[i % frames.length]); i += 1; }, 1000 / fps);
  }

  stop() { if (this.timer) clearInterval(this.timer); this.timer = null; this.frames = null; }

  draw() {
    const {canvas, ctx} = this;
    const W = canvas.width, H = canvas.height;
    ctx.fillStyle = '#ffffff'; ctx.fillRect(0, 0, W, H);
    const cp = Math.cos(this.pitch), sp = Math.sin(this.pitch);
    const eye = [cp * Math.cos(this.yaw), cp * Math.sin(this.yaw), sp];
    const right = [-Math.sin(this.yaw), Math.cos(this.yaw), 0];
    const up = [ // right × (−eye)
      -(right[1] * eye[2] - right[2] * eye[1]), -(right[2] * eye[0] - right[0] * eye[2]),
      -(right[0] * eye[1] - right[1] * eye[0]),
    ];
    if (this.quads) { this._drawQuads(eye, right, up); return; }
    if (this.mesh) { this._drawMesh(eye, right, up); return; }
    if (!this.grid) return;
    const g = this.grid;
    const c = [g.nx / 2, g.ny / 2, g.nz / 2];
    const diag = Math.hypot(g.nx, g.ny, g.nz);
    const scale = this.zoom * 0.95 * Math.min(W, H) / diag;
    const visible = [];
    for (const f of this.faces) {
      const d = DIRS[f[3]];
      if (dot(d.n, eye) <= 0) continue; // back face
      // corner 0 of the face: the voxel's corner on the normal's side
      const o = [f[0] + (d.n[0] > 0 ? 1 : 0), f[1] + (d.n[1] > 0 ? 1 : 0), f[2] + (d.n[2] > 0 ? 1 : 0)];
      const centre = [o[0] + (d.u[0] + d.v[0]) / 2 - c[0], o[1] + (d.u[1] + d.v[1]) / 2 - c[1],
        o[2] + (d.u[2] + d.v[2]) / 2 - c[2]];
      visible.push([dot(centre, eye), f, o, d]);
    }
    visible.sort((a, b) => a[0] - b[0]);
    const project = (p) => {
      const q = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
      return [W / 2 + scale * dot(q, right), H / 2 - scale * dot(q, up)];
    };
    ctx.lineJoin = 'round';
    // thin edges on small faces: dark strokes over 10-pixel faces would turn whole sides dark
    ctx.lineWidth = Math.max(0.3, Math.min(1.2, scale / 30));
    this._polys = [];
    for (const [, f, o, d] of visible) {
      const p3 = [o, [o[0] + d.u[0], o[1] + d.u[1], o[2] + d.u[2]],
        [o[0] + d.u[0] + d.v[0], o[1] + d.u[1] + d.v[1], o[2] + d.u[2] + d.v[2]],
        [o[0] + d.v[0], o[1] + d.v[1], o[2] + d.v[2]]];
      const pts = p3.map(project);
      this._polys.push({name: faceName(f), pts, p3});
      const light = shade(d.n, eye);
      const base = this.layer !== null && f[2] === this.layer ? this.accent : this.color;
      const rgb = base.map((v) => Math.min(255, Math.round(v * light)));
      ctx.beginPath();
      ctx.moveTo(pts[0][0], pts[0][1]);
      for (let i = 1; i < 4; i++) ctx.lineTo(pts[i][0], pts[i][1]);
      ctx.closePath();
      ctx.fillStyle = `rgb(${rgb[0]},${rgb[1]},${rgb[2]})`;
      ctx.fill();
      ctx.strokeStyle = `rgb(${rgb[0] * 0.72 | 0},${rgb[1] * 0.72 | 0},${rgb[2] * 0.72 | 0})`;
      ctx.stroke();
    }
    this._drawHighlight(project);
    if (this.layer !== null) { // the edited layer's frame
      ctx.strokeStyle = 'rgba(194, 99, 43, 0.8)'; ctx.lineWidth = 1.5;
      for (const z of [this.layer, this.layer + 1]) {
        const pts = [[0, 0, z], [g.nx, 0, z], [g.nx, g.ny, z], [0, g.ny, z]].map(project);
        ctx.beginPath(); ctx.moveTo(...pts[0]);
        for (let i = 1; i < 4; i++) ctx.lineTo(...pts[i]);
        ctx.closePath(); ctx.stroke();
      }
    }
  }
}
