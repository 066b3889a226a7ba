// Painting the shape: the palette panel and the paint tools of the 3D view, joining parts, and the shape
// as a file (.vox, .npz) in its colours.
//
// The colours live in the shape's Grid (grid.js: an index per voxel and a 256-row palette, as
// voxfab.shape.VoxelColours keeps them), so every undo step of the layer editor keeps them too: a stroke
// (a drag, a click, a fill) is one step. An uncoloured shape stays uncoloured until it is first painted;
// then its other voxels are white, as VoxelShape.painted makes them. Voxels a drawing adds to a painted
// shape take their nearest coloured voxel's colour, from the server (the library's VoxelColours.fitted).

import {get, post, saveBlob} from './api.js';
import {DIRS, Grid} from './grid.js';

const MOST = 255; // colour indices a palette holds (1..255), as a .vox does
const WHITE = [255, 255, 255, 255];

function same(a, b) { return a[0] === b[0] && a[1] === b[1] && a[2] === b[2] && a[3] === b[3]; }
export function hex(c) { return `#${[0, 1, 2].map((j) => c[j].toString(16).padStart(2, '0')).join('')}`; }
function fromHex(h) { return [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16)).concat(255); }
function row(palette, i) { return palette.subarray(4 * i, 4 * i + 4); }

// Each face's [r, g, b] (its voxel's colour) of a net LAYOUT (faces [x, y, z, dir]) of `grid`; null for an
// uncoloured grid.
export function faceColours(layout, grid) {
  if (!layout || !grid || !grid.colours) return null;
  return layout.faces.map((f) => { const c = grid.rgba(f[0], f[1], f[2]); return c && c.slice(0, 3); });
}

// faceColours as CSS colours, for a net drawn on a canvas (nets.js drawNet's fills).
export function faceFills(layout, grid) {
  const c = faceColours(layout, grid);
  return c && c.map((v) => v && `rgb(${v[0]},${v[1]},${v[2]})`);
}

// Voxels per colour index of a coloured grid.
export function usage(grid) {
  const n = new Uint32Array(256);
  if (grid.colours) for (let i = 0; i < grid.data.length; i++) if (grid.data[i]) n[grid.colours[i]]++;
  return n;
}

// An uncoloured grid made coloured: MagicaVoxel's default palette, every voxel white.
function makeColoured(grid, defaults) {
  grid.palette = Uint8Array.from(defaults.flat());
  const white = defaults.findIndex((c, i) => i > 0 && same(c, WHITE));
  grid.colours = new Uint8Array(grid.data.length);
  for (let i = 0; i < grid.data.length; i++) if (grid.data[i]) grid.colours[i] = white;
}

// The colour index that paints `rgba`: a row of that colour (one the voxels use first), else a row no voxel
// uses, set to it; -1 when every one of the 255 rows is used by another colour.
export function indexFor(grid, rgba) {
  const n = usage(grid), P = grid.palette;
  let match = -1, free = -1;
  for (let i = MOST; i >= 1; i--) {
    if (same(row(P, i), rgba)) { if (n[i]) return i; if (match < 0) match = i; }
    if (!n[i] && free < 0) free = i;
  }
  if (match > 0) return match;
  if (free < 0) return -1;
  P.set(rgba, 4 * free);
  return free;
}

// What a voxel's colour is, to compare colours (two indices of one RGBA are one colour); 0 uncoloured.
function colourKey(grid, i) {
  if (!grid.colours) return 0;
  const c = row(grid.palette, grid.colours[i]);
  return ((c[0] << 24) | (c[1] << 16) | (c[2] << 8) | c[3]) >>> 0;
}

// The voxels (grid indices) of the face region at face d of voxel (x, y, z): the faces turned the same
// way, on the same plane, of the same colour, joined edge to edge across the surface (a flood fill).
export function faceRegion(grid, x, y, z, d) {
  const {n, u, v} = DIRS[d], key = colourKey(grid, grid.index(x, y, z));
  const seen = new Set(), out = [], todo = [[x, y, z]];
  const steps = [u, v, u.map((c) => -c), v.map((c) => -c)];
  while (todo.length) {
    const p = todo.pop(), i = grid.index(...p);
    if (seen.has(i)) continue;
    seen.add(i); out.push(i);
    for (const s of steps) {
      const q = [p[0] + s[0], p[1] + s[1], p[2] + s[2]];
      if (!grid.get(...q) || grid.get(q[0] + n[0], q[1] + n[1], q[2] + n[2])) continue; // no face there
      const j = grid.index(...q);
      if (!seen.has(j) && colourKey(grid, j) === key) todo.push(q);
    }
  }
  return out;
}

// The voxels of the fill at voxel (x, y, z): every voxel of its colour (scope 'all'), or those joined to
// it face to face through voxels of its colour (scope 'connected').
export function fillRegion(grid, x, y, z, scope) {
  const start = grid.index(x, y, z), key = colourKey(grid, start), out = [];
  if (scope === 'all') {
    for (let i = 0; i < grid.data.length; i++) if (grid.data[i] && colourKey(grid, i) === key) out.push(i);
    return out;
  }
  const seen = new Set([start]), todo = [[x, y, z]];
  while (todo.length) {
    const p = todo.pop();
    out.push(grid.index(...p));
    for (const {n} of DIRS) {
      const q = [p[0] + n[0], p[1] + n[1], p[2] + n[2]];
      if (!grid.get(...q)) continue;
      const j = grid.index(...q);
      if (!seen.has(j) && colourKey(grid, j) === key) { seen.add(j); todo.push(q); }
    }
  }
  return out;
}

const FULL = 'This shape already uses 255 colours, as many as a palette holds (a .vox file\'s limit): '
  + 'paint with one of its own colours, or repaint one of them away first.';

export class PaintPanel {
  // editor: the LayerEditor (its grid is the shape, its undo steps ours); viewer: the 3D view; say(text, ok);
  // title(): what files are named after; pitch(): mm per voxel; opened(answer): a file was opened.
  constructor({editor, viewer, say, title, pitch, opened}) {
    Object.assign(this, {editor, viewer, say, title, pitch, opened});
    const $ = (sel) => document.querySelector(sel);
    this.$ = $;
    this.defaults = null; // MagicaVoxel's default palette, [r, g, b, a] rows
    this.current = [224, 48, 48, 255];
    this.tool = 'view'; this.stroke = null; this.editing = false;
    get('/api/palette').then((r) => { this.defaults = r.palette; this.showDefaults(); this.refresh(); }, (e) => say(e));
    for (const r of document.querySelectorAll('input[name=paint-tool]')) {
      r.addEventListener('change', () => { this.tool = r.value; this.arm(); });
    }
    $('#paint-picker').addEventListener('input', () => this.choose(fromHex($('#paint-picker').value)));
    $('#join-parts').addEventListener('click', () => this.join());
    for (const b of document.querySelectorAll('[data-save-as]')) b.addEventListener('click', () => this.save(b.dataset.saveAs));
    $('#open-file').addEventListener('change', () => this.open($('#open-file').files[0]));
    // the tools paint in the 3D view while the Edit tab is open; elsewhere a drag orbits
    for (const b of document.querySelectorAll('#tabs button')) {
      b.addEventListener('click', () => { this.editing = b.dataset.tab === 'edit'; this.arm(); });
    }
    this.showCurrent();
    window.voxfabPaint = this; // for scripts driving the page
  }

  get grid() { return this.editor.grid; }

  arm() {
    const on = this.editing && this.tool !== 'view';
    this.viewer.setTool(on ? {down: (h) => this.down(h), move: (h) => this.move(h), up: () => this.up()} : null);
    document.body.dataset.paintTool = on ? this.tool : '';
  }

  // The colour index a voxel added by hand takes on a coloured shape: the current colour's.
  pen(grid) { const i = indexFor(grid, this.current); return i > 0 ? i : 0; }

  // The current colour, from a swatch, the picker or the eyedropper; a 256th colour is refused.
  choose(rgba) {
    const g = this.grid;
    if (g && g.colours && !this.has(g, rgba) && indexFor(g.clone(), rgba) < 0) { this.say(FULL); return false; }
    this.current = Array.from(rgba.slice(0, 3)).concat(255);
    this.showCurrent();
    return true;
  }

  has(grid, rgba) {
    for (let i = 1; i <= MOST; i++) if (same(row(grid.palette, i), rgba)) return true;
    return false;
  }

  showCurrent() {
    const h = hex(this.current), sw = this.$('#paint-current');
    sw.style.background = h; sw.dataset.colour = h; sw.title = `current colour ${h}`;
    this.$('#paint-picker').value = h;
  }

  swatch(rgba, title) {
    const h = hex(rgba), b = Object.assign(document.createElement('button'), {type: 'button', title});
    b.className = 'swatch'; b.style.background = h; b.dataset.colour = h;
    b.addEventListener('click', () => { if (this.choose(rgba)) this.say(`Painting in ${h}.`, true); });
    return b;
  }

  showDefaults() {
    this.$('#paint-defaults').replaceChildren(...this.defaults.slice(1, MOST + 1).map((c, k) => this.swatch(c, `${hex(c)} (index ${k + 1})`)));
  }

  // The shape's own colours, the used ones first (most voxels first), then the rest of its palette that is
  // not MagicaVoxel's default there; and how many it uses.
  refresh() {
    const g = this.grid, box = this.$('#paint-own');
    if (!g || !g.colours) {
      box.replaceChildren(); this.$('#paint-count').textContent = 'not painted yet';
      box.dataset.count = '0';
      return;
    }
    const n = usage(g), shown = new Set(), swatches = [];
    const used = [...Array(MOST).keys()].map((k) => k + 1).filter((i) => n[i]).sort((a, b) => n[b] - n[a]);
    for (const i of used) {
      const c = Array.from(row(g.palette, i)), h = hex(c);
      if (shown.has(h)) continue;
      shown.add(h); swatches.push(this.swatch(c, `${h}: ${n[i]} voxel${n[i] === 1 ? '' : 's'}`));
    }
    const count = shown.size;
    for (let i = 1; i <= MOST && this.defaults; i++) {
      const c = Array.from(row(g.palette, i)), h = hex(c);
      if (n[i] || shown.has(h) || same(c, this.defaults[i])) continue;
      shown.add(h); swatches.push(this.swatch(c, `${h} (in its palette, not used)`));
    }
    box.replaceChildren(...swatches);
    box.dataset.count = String(count);
    this.$('#paint-count').textContent = `${count} colour${count === 1 ? '' : 's'} of ${MOST}`;
    this.fit();
  }

  // Voxels a drawing added to a painted shape have no colour yet: the server gives them their nearest's.
  async fit() {
    const g = this.grid;
    if (!g || !g.colours) return;
    let missing = false;
    for (let i = 0; i < g.data.length && !missing; i++) missing = g.data[i] && !g.colours[i];
    if (!missing) return;
    const sent = g.data.slice();
    try {
      const r = await post('/api/paint/fit', {grid: g.pack()});
      const fitted = Grid.unpack(r.grid);
      if (g !== this.grid || !fitted.equals(g) || sent.some((v, i) => v !== g.data[i])) return; // edited meanwhile
      g.colours = fitted.colours; g.palette = fitted.palette;
      this.editor.paint(); this.viewer.setGrid(g, this.viewer.layer); this.refresh();
    } catch (e) { this.say(e); }
  }

  // --- a stroke: pointer down, moves, up ------------------------------------------------------------------

  down(hit) {
    if (!hit || !this.defaults) return;
    const g = this.grid;
    if (this.tool === 'pick') {
      const c = g.rgba(hit.x, hit.y, hit.z) || WHITE;
      if (this.choose(c)) this.say(`Picked ${hex(c)} from the voxel at (${hit.x}, ${hit.y}, ${hit.z}).`, true);
      return;
    }
    this.editor.snapshot(); // the shape before the stroke: one undo step
    const fresh = !g.colours;
    if (fresh) makeColoured(g, this.defaults);
    const index = indexFor(g, this.current);
    if (index < 0) { this.editor.undoStack.pop(); this.say(FULL); return; }
    this.stroke = {index, changed: fresh ? g.data.reduce((a, b) => a + b, 0) : 0};
    this.apply(hit);
  }

  move(hit) { if (this.stroke && hit && this.tool === 'voxel') this.apply(hit); }

  apply(hit) {
    const g = this.grid, s = this.stroke;
    const voxels = this.tool === 'face' ? faceRegion(g, hit.x, hit.y, hit.z, hit.d)
      : this.tool === 'fill' ? fillRegion(g, hit.x, hit.y, hit.z, this.$('#fill-scope').value)
        : [g.index(hit.x, hit.y, hit.z)];
    let n = 0;
    for (const i of voxels) if (g.colours[i] !== s.index) { g.colours[i] = s.index; n++; }
    s.changed += n; s.painted = (s.painted || 0) + n;
    if (n) this.editor.onEdit(false);
  }

  up() {
    const s = this.stroke;
    this.stroke = null;
    if (!s) return;
    if (!s.changed) { this.editor.undoStack.pop(); this.say('Those voxels are that colour already.', true); return; }
    this.editor.onEdit(true);
    const what = {voxel: 'voxel', face: 'face region', fill: this.$('#fill-scope').value === 'all'
      ? 'fill of every voxel of that colour' : 'fill of the voxels of that colour touching it'}[this.tool];
    this.say(`Painted ${s.painted || 0} voxel${s.painted === 1 ? '' : 's'} ${hex(this.current)} (${what}); Undo takes the stroke back.`, true);
  }

  // --- the shape's parts, and the shape as a file ------------------------------------------------------------

  async join() {
    const out = this.$('#join-result');
    try {
      const r = await post('/api/join', {grid: this.grid.pack()});
      out.replaceChildren(...r.joins.map((j) => Object.assign(document.createElement('li'), {textContent: j.words})));
      out.dataset.joins = String(r.joins.length);
      if (!r.joins.length) { this.say('The shape is one piece already: nothing to join.', true); return; }
      this.editor.snapshot(); // the whole join is one undo step
      this.grid.assign(Grid.unpack(r.grid));
      this.editor.paint(); this.editor.onEdit(true);
      const added = r.joins.reduce((a, j) => a + j.added.length, 0);
      this.say(`Joined ${r.joins.length} part${r.joins.length === 1 ? '' : 's'} to the shape with ${added} voxel${added === 1 ? '' : 's'}, `
        + 'each in a neighbour\'s colour (listed under Join parts; Undo takes them back).', true);
    } catch (e) { this.say(e); }
  }

  async save(kind) {
    try {
      const resp = await fetch('/api/shape/file', {method: 'POST', headers: {'Content-Type': 'application/json'},
        body: JSON.stringify({grid: this.grid.pack(), format: kind, title: this.title(), pitch: this.pitch()})});
      if (!resp.ok) throw new Error((await resp.json()).error);
      const name = /filename="([^"]+)"/.exec(resp.headers.get('content-disposition'))[1];
      saveBlob(await resp.blob(), name);
      const colours = this.grid.colours ? 'in its colours' : 'uncoloured';
      this.say(`Saved ${name}, ${colours}${kind === 'npz' ? ', at its scale' : ''}.`, true);
    } catch (e) { this.say(e); }
  }

  async open(file) {
    if (!file) return;
    try {
      const resp = await fetch(`/api/shape/open?name=${encodeURIComponent(file.name)}`, {method: 'POST', body: file});
      const r = await resp.json();
      if (!resp.ok) throw new Error(r.error);
      this.opened(r);
      this.say([`Opened ${r.label}`, ...r.notes].join('; '), true);
    } catch (e) { this.say(e); } finally { this.$('#open-file').value = ''; }
  }
}
