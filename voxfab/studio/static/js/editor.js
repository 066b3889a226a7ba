// Layer-by-layer voxel editing with undo and redo (one step per stroke).

export class LayerEditor {
  // tag(): what the page attaches to each undo step (its state of the shape then), given back as `this.tag`
  // when the step is restored.
  constructor(canvas, {onEdit, tag = () => null}) {
    this.canvas = canvas; this.onEdit = onEdit; this.tagOf = tag;
    this.grid = null; this.layer = 12; this.undoStack = []; this.redoStack = []; this.tag = null;
    let painting = null; // 1: adding, 0: removing, null: idle
    const cellAt = (e) => {
      const r = canvas.getBoundingClientRect();
      const n = this.grid.nx, cell = canvas.width / n;
      const x = Math.floor((e.clientX - r.left) * canvas.width / r.width / cell);
      const yFromTop = Math.floor((e.clientY - r.top) * canvas.height / r.height / cell);
      const y = this.grid.ny - 1 - yFromTop; // y up, as in the 3D view from above
      return x >= 0 && y >= 0 && x < this.grid.nx && y < this.grid.ny ? [x, y] : null;
    };
    canvas.addEventListener('pointerdown', (e) => {
      if (!this.grid) return;
      const c = cellAt(e);
      if (!c) return;
      canvas.setPointerCapture(e.pointerId);
      this.snapshot();
      painting = this.grid.get(c[0], c[1], this.layer) ? 0 : 1;
      this.grid.set(c[0], c[1], this.layer, painting);
      this.paint(); this.onEdit(false);
    });
    canvas.addEventListener('pointermove', (e) => {
      if (painting === null) return;
      const c = cellAt(e);
      if (!c || this.grid.get(c[0], c[1], this.layer) === painting) return;
      this.grid.set(c[0], c[1], this.layer, painting);
      this.paint(); this.onEdit(false);
    });
    const up = () => { if (painting !== null) { painting = null; this.onEdit(true); } };
    canvas.addEventListener('pointerup', up);
    canvas.addEventListener('pointercancel', up);
  }

  setGrid(grid, {keepHistory = false} = {}) {
    this.grid = grid;
    if (!keepHistory) { this.undoStack = []; this.redoStack = []; }
    this.paint();
  }

  // Each undo step keeps the grid and the page's tag of it (the drawing's shape then, the shape's names),
  // restored with it: the page knows which hand edits each step had, and what the shape was called.
  entry(grid) { return {grid: grid.clone(), tag: this.tagOf()}; }

  // Keep a shape that is about to be replaced (by a new drawing, an opened shape) one Undo away.
  remember(grid, tag) {
    if (!grid || !grid.count()) return;
    this.undoStack.push({grid: grid.clone(), tag});
    if (this.undoStack.length > 200) this.undoStack.shift();
    this.redoStack = [];
  }

  setLayer(z) { this.layer = Math.max(0, Math.min(this.grid ? this.grid.nz - 1 : 24, z)); this.paint(); }

  snapshot() {
    this.undoStack.push(this.entry(this.grid));
    if (this.undoStack.length > 200) this.undoStack.shift();
    this.redoStack = [];
  }

  restore(e) { this.grid.data.set(e.grid.data); this.tag = e.tag; this.paint(); }

  undo() {
    if (!this.undoStack.length) return false;
    this.redoStack.push(this.entry(this.grid));
    this.restore(this.undoStack.pop());
    return true;
  }

  redo() {
    if (!this.redoStack.length) return false;
    this.undoStack.push(this.entry(this.grid));
    this.restore(this.redoStack.pop());
    return true;
  }

  clearLayer() {
    this.snapshot();
    for (let x = 0; x < this.grid.nx; x++) for (let y = 0; y < this.grid.ny; y++) this.grid.set(x, y, this.layer, 0);
    this.paint();
  }

  copyBelow() {
    if (this.layer === 0) return;
    this.snapshot();
    for (let x = 0; x < this.grid.nx; x++) for (let y = 0; y < this.grid.ny; y++) {
      this.grid.set(x, y, this.layer, this.grid.get(x, y, this.layer - 1));
    }
    this.paint();
  }

  paint() {
    const c = this.canvas, ctx = c.getContext('2d'), g = this.grid;
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, c.width, c.height);
    if (!g) return;
    const cell = c.width / g.nx;
    for (let x = 0; x < g.nx; x++) for (let y = 0; y < g.ny; y++) {
      const top = (g.ny - 1 - y) * cell;
      if (g.get(x, y, this.layer)) ctx.fillStyle = '#c2632b';
      else if (g.get(x, y, this.layer - 1)) ctx.fillStyle = '#f1dcc9';
      else continue;
      ctx.fillRect(x * cell + 1, top + 1, cell - 2, cell - 2);
    }
    ctx.strokeStyle = '#e6e0d6'; ctx.lineWidth = 1;
    for (let i = 0; i <= g.nx; i++) {
      ctx.beginPath(); ctx.moveTo(i * cell + 0.5, 0); ctx.lineTo(i * cell + 0.5, c.height); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(0, i * cell + 0.5); ctx.lineTo(c.width, i * cell + 0.5); ctx.stroke();
    }
  }
}
