// A voxel grid [x, y, z] (z up) as one byte per voxel, maybe with colours, and its packed wire form.
//
// A coloured grid also has `colours` (one byte per voxel: its colour index 1..255, 0 where empty) and
// `palette` (256 RGBA rows, 1024 bytes: row i is colour index i), as voxfab.shape.VoxelColours keeps them.
// An uncoloured grid has neither (null) and is sent as it always was.

export const SIDE = 25;

function b64(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 4096) s += String.fromCharCode(...bytes.subarray(i, i + 4096));
  return btoa(s);
}
function unb64(text) { const raw = atob(text); return Uint8Array.from(raw, (c) => c.charCodeAt(0)); }

export class Grid {
  constructor(nx = SIDE, ny = SIDE, nz = SIDE, data = null, colours = null, palette = null) {
    this.nx = nx; this.ny = ny; this.nz = nz;
    this.data = data || new Uint8Array(nx * ny * nz);
    this.colours = colours; this.palette = palette;
  }
  index(x, y, z) { return (x * this.ny + y) * this.nz + z; }
  get(x, y, z) {
    if (x < 0 || y < 0 || z < 0 || x >= this.nx || y >= this.ny || z >= this.nz) return 0;
    return this.data[this.index(x, y, z)];
  }
  // Fill or empty a voxel; on a coloured grid a voxel filled takes `colour` (an index), else keeps its own
  // (a new one has none, 0, until the server fits it: paint.js fitColours).
  set(x, y, z, v, colour = 0) {
    const i = this.index(x, y, z);
    this.data[i] = v ? 1 : 0;
    if (this.colours) this.colours[i] = v ? colour || this.colours[i] : 0;
  }
  // [r, g, b, a] of a filled voxel of a coloured grid, else null.
  rgba(x, y, z) {
    if (!this.colours || !this.get(x, y, z)) return null;
    const c = this.colours[this.index(x, y, z)];
    return c ? Array.from(this.palette.subarray(4 * c, 4 * c + 4)) : null;
  }
  clone() {
    return new Grid(this.nx, this.ny, this.nz, this.data.slice(), this.colours && this.colours.slice(),
      this.palette && this.palette.slice());
  }
  // Take another grid's voxels and colours (an undo step restored).
  assign(o) {
    this.data.set(o.data);
    this.colours = o.colours && o.colours.slice(); this.palette = o.palette && o.palette.slice();
  }
  count() { let n = 0; for (const v of this.data) n += v; return n; }
  equals(o) {
    if (!o || o.data.length !== this.data.length) return false;
    for (let i = 0; i < this.data.length; i++) if (o.data[i] !== this.data[i]) return false;
    return true;
  }

  // {"dims": [X, Y, Z], "bits": base64}, most significant bit first, as numpy.packbits.
  // With colours: "colours" (each filled voxel's index, in bit order) and "palette" (1024 bytes), base64.
  static unpack(p) {
    const [nx, ny, nz] = p.dims;
    const raw = atob(p.bits);
    const g = new Grid(nx, ny, nz);
    for (let i = 0; i < g.data.length; i++) {
      g.data[i] = (raw.charCodeAt(i >> 3) >> (7 - (i & 7))) & 1;
    }
    if (p.colours) {
      const per = unb64(p.colours);
      g.colours = new Uint8Array(g.data.length); g.palette = unb64(p.palette);
      let k = 0;
      for (let i = 0; i < g.data.length; i++) if (g.data[i]) g.colours[i] = per[k++];
    }
    return g;
  }
  pack() {
    const bytes = new Uint8Array((this.data.length + 7) >> 3);
    for (let i = 0; i < this.data.length; i++) if (this.data[i]) bytes[i >> 3] |= 0x80 >> (i & 7);
    const out = {dims: [this.nx, this.ny, this.nz], bits: b64(bytes)};
    if (this.colours) {
      const per = [];
      for (let i = 0; i < this.data.length; i++) if (this.data[i]) per.push(this.colours[i]);
      out.colours = b64(Uint8Array.from(per)); out.palette = b64(this.palette);
    }
    return out;
  }
}

// The hand edits (voxels where `shape` differs from `base`) laid on `fresh`; returns [grid, count].
// A painted shape's colours go with it: the voxels it had keep theirs, the drawing's new ones have none
// until the server gives them their nearest's (paint.js fitColours).
export function carryEdits(base, shape, fresh) {
  const out = fresh.clone();
  let n = 0;
  for (let i = 0; i < out.data.length; i++) {
    if (shape.data[i] !== base.data[i]) { out.data[i] = shape.data[i]; n++; }
  }
  if (shape.colours) {
    out.palette = shape.palette.slice(); out.colours = new Uint8Array(out.data.length);
    for (let i = 0; i < out.data.length; i++) if (out.data[i] && shape.data[i]) out.colours[i] = shape.colours[i];
  }
  return [out, n];
}

// The six face directions: normal, and the two in-plane axes (counter-clockwise seen from outside).
export const DIRS = [
  {n: [1, 0, 0], u: [0, 1, 0], v: [0, 0, 1]}, {n: [-1, 0, 0], u: [0, 0, 1], v: [0, 1, 0]},
  {n: [0, 1, 0], u: [0, 0, 1], v: [1, 0, 0]}, {n: [0, -1, 0], u: [1, 0, 0], v: [0, 0, 1]},
  {n: [0, 0, 1], u: [1, 0, 0], v: [0, 1, 0]}, {n: [0, 0, -1], u: [0, 1, 0], v: [1, 0, 0]},
];

// Exposed faces: [x, y, z, d] for each filled voxel side whose neighbour is empty.
export function exposedFaces(g) {
  const out = [];
  for (let x = 0; x < g.nx; x++) for (let y = 0; y < g.ny; y++) for (let z = 0; z < g.nz; z++) {
    if (!g.data[g.index(x, y, z)]) continue;
    for (let d = 0; d < 6; d++) {
      const n = DIRS[d].n;
      if (!g.get(x + n[0], y + n[1], z + n[2])) out.push([x, y, z, d]);
    }
  }
  return out;
}
