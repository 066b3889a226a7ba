// A small voxel viewer on a 2D canvas: orthographic orbit camera, painter's order, shaded faces
// with dark voxel edges. Drag to orbit, wheel to zoom. No WebGL needed, so it runs anywhere.

import {DIRS, exposedFaces} from './grid.js';

const LIGHT = normalize([0.45, 0.3, 0.85]);

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
    canvas.addEventListener('pointerdown', (e) => {
      this._drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); canvas.style.cursor = 'grabbing';
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!this._drag) return;
      const [x0, y0] = this._drag; this._drag = [e.clientX, e.clientY];
      this.yaw -= (e.clientX - x0) * 0.01;
      this.pitch = Math.max(-1.5, Math.min(1.5, this.pitch + (e.clientY - y0) * 0.01));
      this.draw();
    });
    const end = () => { this._drag = null; canvas.style.cursor = 'grab'; };
    canvas.addEventListener('pointerup', end);
    canvas.addEventListener('pointercancel', end);
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      this.zoom = Math.max(0.3, Math.min(6, this.zoom * Math.exp(-e.deltaY * 0.0015)));
      this.draw();
    }, {passive: false});
  }

  // Show a grid; `layer` (a z index or null) is highlighted for the editor.
  setGrid(grid, layer = this.layer) {
    this.grid = grid; this.layer = layer; this.mesh = null;
    this.faces = exposedFaces(grid);
    this.version += 1;
    this.canvas.dataset.version = String(this.version);
    this.canvas.dataset.faces = String(this.faces.length);
    this.draw();
  }

  setLayer(layer) { this.layer = layer; this.draw(); }

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
      const light = 0.55 + 0.45 * Math.abs(dot(t.n, LIGHT));
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
    ctx.lineWidth = Math.max(0.4, Math.min(1.2, scale / 20));
    for (const [, f, o, d] of visible) {
      const pts = [o, [o[0] + d.u[0], o[1] + d.u[1], o[2] + d.u[2]],
        [o[0] + d.u[0] + d.v[0], o[1] + d.u[1] + d.v[1], o[2] + d.u[2] + d.v[2]],
        [o[0] + d.v[0], o[1] + d.v[1], o[2] + d.v[2]]].map(project);
      const light = 0.5 + 0.5 * Math.max(0, dot(d.n, LIGHT)) + 0.08 * dot(d.n, eye);
      const base = this.layer !== null && f[2] === this.layer ? this.accent : this.color;
      const rgb = base.map((v) => Math.min(255, Math.round(v * light)));
      ctx.beginPath();
      ctx.moveTo(pts[0][0], pts[0][1]);
      for (let i = 1; i < 4; i++) ctx.lineTo(pts[i][0], pts[i][1]);
      ctx.closePath();
      ctx.fillStyle = `rgb(${rgb[0]},${rgb[1]},${rgb[2]})`;
      ctx.fill();
      ctx.strokeStyle = `rgb(${rgb[0] * 0.55 | 0},${rgb[1] * 0.55 | 0},${rgb[2] * 0.55 | 0})`;
      ctx.stroke();
    }
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
