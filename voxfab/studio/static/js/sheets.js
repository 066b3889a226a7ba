// The pieces of a net on their sheets (the contract's PLACEMENT): one canvas per sheet, and an empty one to
// start a new sheet. Drag a piece to move it by whole faces, onto another sheet too; R or turn() turns the
// chosen piece a quarter turn counter-clockwise about its middle. The server checks the layout (overlap,
// margin and the room for tabs) when it draws the files, so what is shown is what is made.

const VIEW_W = 170; // px of a sheet's canvas width
const COLORS = ['#f6d7a7', '#bfe0c4', '#c9d6f2', '#f2c9d9', '#e2d3f0', '#d9ecb8', '#f0dfc0', '#c4e6e8'];

// A face corner (cells, the piece's own frame) turned `turns` quarter turns counter-clockwise.
export function turn(x, y, turns) {
  for (let t = 0; t < turns % 4; t++) [x, y] = [-y, x];
  return [x, y];
}

function copyPlacement(p) { return JSON.parse(JSON.stringify(p)); }

// Sheets side by side in faces, two faces apart: where sheet k starts across.
function sheetStride(placement) { return placement.sheet[0] / placement.face_size + 2; }

// Sheet k as [x0, y0, x1, y1] in the cells of placedLayout.
export function sheetRect(placement, k) {
  const f = placement.face_size, [W, H] = placement.sheet, x = k * sheetStride(placement);
  return [x, 0, x + W / f, H / f];
}

// The layout with every face where its piece sits, in cells; sheets side by side (for the net views).
export function placedLayout(layout, placement) {
  if (!placement) return layout; // a net that does not fit the sheet has no place on it: as unfolded
  const f = placement.face_size, stride = sheetStride(placement);
  const corners = layout.corners.slice();
  for (let i = 0; i < layout.faces.length; i++) {
    const p = placement.pieces[layout.piece ? layout.piece[i] : 0];
    for (let k = 0; k < 4; k++) {
      const [x, y] = turn(layout.corners[8 * i + 2 * k], layout.corners[8 * i + 2 * k + 1], p.turns);
      corners[8 * i + 2 * k] = p.x / f + x + p.sheet * stride;
      corners[8 * i + 2 * k + 1] = p.y / f + y;
    }
  }
  return {...layout, corners};
}

export class SheetBoard {
  constructor(box, {onChange, onSelect}) {
    this.box = box; this.onChange = onChange; this.onSelect = onSelect || (() => {});
    this.layout = null; this.placement = null; this.selected = null; this.drag = null;
    document.addEventListener('keydown', (e) => {
      if ((e.key === 'r' || e.key === 'R') && this.placement && this.selected !== null
          && !/^(INPUT|SELECT|TEXTAREA)$/.test(document.activeElement.tagName)) {
        e.preventDefault(); this.turn();
      }
    });
  }

  // Show a net (its LAYOUT) placed as `placement`; null clears the board.
  setNet(layout, placement) {
    this.layout = layout; this.placement = placement ? copyPlacement(placement) : null;
    this.selected = null; this.pivot = null;
    // Faces of each piece, for drawing and hit tests.
    this.members = [];
    if (layout) {
      for (let i = 0; i < layout.faces.length; i++) {
        const q = layout.piece ? layout.piece[i] : 0;
        (this.members[q] = this.members[q] || []).push(i);
      }
      this.folds = new Set();
      const fo = layout.folds;
      for (let i = 0; i < fo.length; i += 2) this.folds.add(`${Math.min(fo[i], fo[i + 1])}-${Math.max(fo[i], fo[i + 1])}`);
    }
    this.build();
  }

  get scale() { return VIEW_W / this.placement.sheet[0]; }

  build() {
    this.box.replaceChildren();
    this.canvases = [];
    if (!this.placement) { delete this.box.dataset.placement; return; }
    const [W, H] = this.placement.sheet, s = this.scale;
    for (let k = 0; k <= this.placement.sheets; k++) {
      const fig = document.createElement('figure');
      const cv = Object.assign(document.createElement('canvas'), {width: Math.round(W * s), height: Math.round(H * s)});
      cv.dataset.sheet = String(k);
      cv.setAttribute('data-testid', 'net-sheet-view');
      const fresh = k === this.placement.sheets;
      if (fresh) cv.classList.add('new-sheet');
      cv.addEventListener('pointerdown', (e) => this.down(e, k));
      const cap = document.createElement('figcaption');
      cap.textContent = fresh ? 'drop a piece here for a new sheet' : `sheet ${k + 1} of ${this.placement.sheets}`;
      fig.append(cv, cap);
      this.box.append(fig);
      this.canvases.push(cv);
    }
    this.draw();
  }

  // The four corners in mm of face i of piece q placed at `place` (default: its placement).
  faceMm(i, place) {
    const f = this.placement.face_size, c = this.layout.corners, out = [];
    for (let k = 0; k < 4; k++) {
      const [x, y] = turn(c[8 * i + 2 * k], c[8 * i + 2 * k + 1], place.turns);
      out.push([place.x + x * f, place.y + y * f]);
    }
    return out;
  }

  pieceBox(q, place) {
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (const i of this.members[q]) {
      for (const [x, y] of this.faceMm(i, place)) {
        x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
      }
    }
    return [x0, y0, x1, y1];
  }

  draw() {
    if (!this.placement) return;
    const [W, H] = this.placement.sheet, m = this.placement.margin, s = this.scale;
    this.box.dataset.placement = JSON.stringify(this.placement);
    this.canvases.forEach((cv, k) => {
      const ctx = cv.getContext('2d');
      ctx.clearRect(0, 0, cv.width, cv.height);
      ctx.strokeStyle = '#c8c0b4'; ctx.setLineDash([4, 3]); ctx.lineWidth = 1;
      ctx.strokeRect(m * s, m * s, (W - 2 * m) * s, (H - 2 * m) * s);
      ctx.setLineDash([]);
      this.placement.pieces.forEach((p, q) => {
        let place = p;
        if (this.drag && this.drag.piece === q) {
          if (this.drag.sheet !== k) return;
          place = this.drag.place;
        } else if (p.sheet !== k) return;
        this.drawPiece(ctx, q, place, H, s);
      });
    });
  }

  drawPiece(ctx, q, place, H, s) {
    const toPx = ([x, y]) => [x * s, (H - y) * s];
    ctx.fillStyle = COLORS[q % COLORS.length];
    ctx.strokeStyle = q === this.selected ? '#c2632b' : '#b5ab9c';
    ctx.lineWidth = q === this.selected ? 1.2 : 0.4;
    const cuts = new Path2D();
    let cx = 0, cy = 0;
    for (const i of this.members[q]) {
      const pts = this.faceMm(i, place).map(toPx);
      ctx.beginPath();
      pts.forEach((pt, k) => ctx[k ? 'lineTo' : 'moveTo'](...pt));
      ctx.closePath(); ctx.fill();
      for (let k = 0; k < 4; k++) {
        const j = this.layout.neighbor[4 * i + k];
        if (!this.folds.has(`${Math.min(i, j)}-${Math.max(i, j)}`)) { cuts.moveTo(...pts[k]); cuts.lineTo(...pts[(k + 1) % 4]); }
      }
      cx += pts[0][0] + pts[2][0]; cy += pts[0][1] + pts[2][1];
    }
    ctx.strokeStyle = q === this.selected ? '#c2632b' : '#d03030';
    ctx.stroke(cuts);
    const n = 2 * this.members[q].length;
    ctx.fillStyle = '#333'; ctx.font = '11px system-ui'; ctx.textAlign = 'center'; ctx.textBaseline = 'middle';
    ctx.fillText(`(${q + 1})`, cx / n, cy / n);
  }

  // mm on sheet canvas `cv` of a pointer event.
  mm(cv, e) {
    const r = cv.getBoundingClientRect(), s = this.scale;
    const px = (e.clientX - r.left) * cv.width / r.width, py = (e.clientY - r.top) * cv.height / r.height;
    return [px / s, this.placement.sheet[1] - py / s];
  }

  pieceAt(k, [x, y]) {
    for (let q = this.placement.pieces.length - 1; q >= 0; q--) {
      const p = this.placement.pieces[q];
      if (p.sheet !== k) continue;
      for (const i of this.members[q]) {
        const pts = this.faceMm(i, p), xs = pts.map((t) => t[0]), ys = pts.map((t) => t[1]);
        if (x >= Math.min(...xs) && x <= Math.max(...xs) && y >= Math.min(...ys) && y <= Math.max(...ys)) return q;
      }
    }
    return null;
  }

  // Snap (x, y) mm to the face grid the pieces share (that of the first piece).
  snap(x, y) {
    const f = this.placement.face_size, a = this.placement.pieces[0];
    return [a.x + Math.round((x - a.x) / f) * f, a.y + Math.round((y - a.y) / f) * f];
  }

  down(e, k) {
    if (!this.placement) return;
    const at = this.mm(e.currentTarget, e), q = this.pieceAt(k, at);
    this.select(q);
    if (q === null) return;
    e.preventDefault();
    const start = this.placement.pieces[q];
    this.drag = {piece: q, sheet: k, from: at, start, place: {...start}};
    const move = (ev) => this.move(ev);
    const up = (ev) => {
      document.removeEventListener('pointermove', move); document.removeEventListener('pointerup', up);
      this.drop(ev);
    };
    document.addEventListener('pointermove', move); document.addEventListener('pointerup', up);
  }

  // The sheet canvas under a pointer event, or null.
  sheetUnder(e) {
    const hit = document.elementFromPoint(e.clientX, e.clientY);
    return this.canvases.includes(hit) ? hit : null;
  }

  move(e) {
    const d = this.drag, cv = this.sheetUnder(e);
    if (!d || !cv) return;
    const k = Number(cv.dataset.sheet), [x, y] = this.mm(cv, e);
    d.sheet = k;
    if (k === this.placement.sheets) d.place = {...d.start, sheet: k, ...this.centred(d.piece, d.start)};
    else {
      const [sx, sy] = this.snap(d.start.x + x - d.from[0], d.start.y + y - d.from[1]);
      d.place = {...d.start, sheet: k, x: sx, y: sy};
    }
    this.draw();
  }

  // x, y that put the piece in the middle of an empty sheet, on the face grid.
  centred(q, place) {
    const [x0, y0, x1, y1] = this.pieceBox(q, {...place, x: 0, y: 0});
    const [W, H] = this.placement.sheet;
    const [x, y] = this.snap(W / 2 - (x0 + x1) / 2, H / 2 - (y0 + y1) / 2);
    return {x, y};
  }

  drop(e) {
    const d = this.drag;
    if (!d) return;
    this.move(e); // the final spot, if the pointer moved since the last event
    this.drag = null;
    const moved = d.place.x !== d.start.x || d.place.y !== d.start.y || d.place.sheet !== d.start.sheet;
    if (!moved) { this.draw(); return; }
    this.placement.pieces[d.piece] = {...d.start, x: d.place.x, y: d.place.y, sheet: d.sheet};
    this.commit();
  }

  // Turn the chosen piece a quarter turn counter-clockwise about its middle (on the face grid). Turns in a
  // row keep the first one's middle, so two make an exact half turn and four bring the piece back.
  turn() {
    const q = this.selected;
    if (q === null || !this.placement) return;
    const p = this.placement.pieces[q];
    if (!this.pivot || this.pivot.piece !== q) {
      const [a0, b0, a1, b1] = this.pieceBox(q, p);
      this.pivot = {piece: q, at: [(a0 + a1) / 2, (b0 + b1) / 2]};
    }
    const turned = {...p, turns: (p.turns + 1) % 4};
    const [c0, d0, c1, d1] = this.pieceBox(q, {...turned, x: 0, y: 0});
    const [x, y] = this.snap(this.pivot.at[0] - (c0 + c1) / 2, this.pivot.at[1] - (d0 + d1) / 2);
    this.placement.pieces[q] = {...turned, x, y};
    this.commit();
  }

  select(q) {
    this.selected = q; this.pivot = null;
    this.draw();
    this.onSelect(q);
  }

  // Drop emptied sheets (renumbering the rest), count the sheets, redraw and tell the page.
  commit() {
    const used = [...new Set(this.placement.pieces.map((p) => p.sheet))].sort((a, b) => a - b);
    this.placement.pieces = this.placement.pieces.map((p) => ({...p, sheet: used.indexOf(p.sheet)}));
    const grew = used.length !== this.placement.sheets;
    this.placement.sheets = used.length;
    if (grew) this.build(); else this.draw();
    this.onChange(copyPlacement(this.placement));
  }
}
