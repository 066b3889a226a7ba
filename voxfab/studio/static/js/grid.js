// A voxel grid [x, y, z] (z up) as one byte per voxel, and its packed wire form.

export const SIDE = 25;

export class Grid {
  constructor(nx = SIDE, ny = SIDE, nz = SIDE, data = null) {
    this.nx = nx; this.ny = ny; this.nz = nz;
    this.data = data || new Uint8Array(nx * ny * nz);
  }
  index(x, y, z) { return (x * this.ny + y) * this.nz + z; }
  get(x, y, z) {
    if (x < 0 || y < 0 || z < 0 || x >= this.nx || y >= this.ny || z >= this.nz) return 0;
    return this.data[this.index(x, y, z)];
  }
  set(x, y, z, v) { this.data[this.index(x, y, z)] = v ? 1 : 0; }
  clone() { return new Grid(this.nx, this.ny, this.nz, this.data.slice()); }
  count() { let n = 0; for (const v of this.data) n += v; return n; }
  equals(o) {
    if (!o || o.data.length !== this.data.length) return false;
    for (let i = 0; i < this.data.length; i++) if (o.data[i] !== this.data[i]) return false;
    return true;
  }

  // {"dims": [X, Y, Z], "bits": base64}, most significant bit first, as numpy.packbits.
  static unpack(p) {
    const [nx, ny, nz] = p.dims;
    const raw = atob(p.bits);
    const g = new Grid(nx, ny, nz);
    for (let i = 0; i < g.data.length; i++) {
      g.data[i] = (raw.charCodeAt(i >> 3) >> (7 - (i & 7))) & 1;
    }
    return g;
  }
  pack() {
    const bytes = new Uint8Array((this.data.length + 7) >> 3);
    for (let i = 0; i < this.data.length; i++) if (this.data[i]) bytes[i >> 3] |= 0x80 >> (i & 7);
    let s = '';
    for (let i = 0; i < bytes.length; i += 4096) s += String.fromCharCode(...bytes.subarray(i, i + 4096));
    return {dims: [this.nx, this.ny, this.nz], bits: btoa(s)};
  }
}

// The hand edits (voxels where `shape` differs from `base`) laid on `fresh`; returns [grid, count].
export function carryEdits(base, shape, fresh) {
  const out = fresh.clone();
  let n = 0;
  for (let i = 0; i < out.data.length; i++) {
    if (shape.data[i] !== base.data[i]) { out.data[i] = shape.data[i]; n++; }
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
