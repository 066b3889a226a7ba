// Drawing inputs: a 2D curve source (freehand or polyline strokes, an expression, or a bitmap),
// a spine drawn in top view, and foci placed by clicking.

// The spine presets of the tube's menu: x(t), y(t), z(t) for t from 0 to 1.
export const SPINES = {
  circle: ['cos(2*pi*t)', 'sin(2*pi*t)', '0'],
  trefoil: ['sin(2*pi*t) + 2*sin(4*pi*t)', 'cos(2*pi*t) - 2*cos(4*pi*t)', '-sin(6*pi*t)'],
  helix: ['cos(6*pi*t)', 'sin(6*pi*t)', '2*t'],
  wave: ['4*t', '0', '0.6*sin(4*pi*t)'],
};

const AXIS_X = 20; // the generatrix canvas's axis, in canvas pixels from the left

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v; else if (k in e && typeof v !== 'string') e[k] = v; else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

function canvasPoint(canvas, ev) {
  const r = canvas.getBoundingClientRect();
  return [(ev.clientX - r.left) * canvas.width / r.width, (ev.clientY - r.top) * canvas.height / r.height];
}

// One curve source: the page's JSON {"kind": "expr" | "drawn" | "bitmap", ...}.
export class CurveSource {
  constructor(box, {expr, onChange, axis = false}) {
    this.box = box; this.role = box.dataset.role; this.onChange = onChange; this.axis = axis;
    this.kind = 'expr'; this.polylines = []; this.current = null; this.bitmap = null; this.bitmapImage = null;
    const name = `kind-${this.role}`;
    const radio = (value, label) => el('label', {}, el('input', {type: 'radio', name, value}), ` ${label}`);
    this.kindRow = el('div', {class: 'row'}, radio('drawn', 'draw'), radio('expr', 'expression'),
      radio('bitmap', 'bitmap'));
    this.kindRow.querySelector('input[value=expr]').checked = true;
    this.tool = el('select', {class: 'tool'}, el('option', {value: 'freehand'}, 'freehand'),
      el('option', {value: 'polyline'}, 'polyline'));
    this.closed = el('input', {type: 'checkbox', class: 'closed'});
    this.finishBtn = el('button', {type: 'button', class: 'finish'}, 'finish');
    this.undoBtn = el('button', {type: 'button', class: 'undo-stroke'}, 'undo stroke');
    this.clearBtn = el('button', {type: 'button', class: 'clear'}, 'clear');
    this.canvas = el('canvas', {width: 276, height: 276, class: 'draw'});
    this.drawPart = el('div', {class: 'draw-part hidden'},
      el('div', {class: 'tools'}, this.tool, el('label', {}, this.closed, ' closed'), this.finishBtn,
        this.undoBtn, this.clearBtn),
      this.canvas);
    this.text = el('input', {type: 'text', class: 'expr', value: expr, spellcheck: false});
    this.exprPart = el('div', {class: 'expr-part'}, this.text);
    this.file = el('input', {type: 'file', accept: 'image/png,image/gif,image/bmp', class: 'bitmap'});
    this.bitmapPart = el('div', {class: 'bitmap-part hidden'}, this.file,
      el('p', {class: 'hint'}, 'dark pixels are inside'));
    box.append(el('h3', {}, box.dataset.title), this.kindRow, this.drawPart, this.exprPart, this.bitmapPart);

    this.kindRow.addEventListener('change', (e) => { this.setKind(e.target.value); this.onChange(true); });
    this.text.addEventListener('change', () => this.onChange(true));
    this.file.addEventListener('change', () => this.loadBitmap());
    this.finishBtn.addEventListener('click', () => { this.finish(); this.onChange(true); });
    this.undoBtn.addEventListener('click', () => { this.polylines.pop(); this.current = null; this.paint(); this.onChange(true); });
    this.clearBtn.addEventListener('click', () => { this.polylines = []; this.current = null; this.paint(); this.onChange(true); });
    this.closed.addEventListener('change', () => {
      // the flag applies to the last stroke too, so a stroke can be closed after the fact
      const last = this.polylines[this.polylines.length - 1];
      if (last && !this.current) { last.closed = this.closed.checked; this.paint(); this.onChange(true); }
    });
    this.bindCanvas();
    this.paint();
  }

  setKind(kind) {
    this.kind = kind;
    this.kindRow.querySelector(`input[value=${kind}]`).checked = true;
    this.drawPart.classList.toggle('hidden', kind !== 'drawn');
    this.exprPart.classList.toggle('hidden', kind !== 'expr');
    this.bitmapPart.classList.toggle('hidden', kind !== 'bitmap');
    this.paint();
  }

  bindCanvas() {
    const c = this.canvas;
    let down = false, last = null;
    c.addEventListener('pointerdown', (e) => {
      const p = canvasPoint(c, e);
      if (this.tool.value === 'polyline') {
        if (!this.current) { this.current = {points: [], closed: false}; this.polylines.push(this.current); }
        this.current.points.push(p); this.paint(); this.onChange(false);
        return;
      }
      c.setPointerCapture(e.pointerId);
      down = true; last = p;
      this.current = {points: [p], closed: false};
      this.polylines.push(this.current);
    });
    c.addEventListener('pointermove', (e) => {
      if (!down) return;
      const p = canvasPoint(c, e);
      if (Math.hypot(p[0] - last[0], p[1] - last[1]) < 2) return;
      this.current.points.push(p); last = p; this.paint(); this.onChange(false);
    });
    const up = () => {
      if (!down) return;
      down = false;
      this.finish();
      this.onChange(true);
    };
    c.addEventListener('pointerup', up);
    c.addEventListener('pointercancel', up);
    c.addEventListener('dblclick', () => { if (this.tool.value === 'polyline') { this.finish(); this.onChange(true); } });
  }

  finish() {
    if (!this.current) return;
    if (this.current.points.length < 2) this.polylines.pop();
    else this.current.closed = this.closed.checked;
    this.current = null; this.paint();
  }

  loadBitmap() {
    const f = this.file.files[0];
    if (!f) return;
    const reader = new FileReader();
    reader.onload = () => {
      this.bitmap = reader.result.split(',')[1];
      const img = new Image();
      img.onload = () => { this.bitmapImage = img; this.paint(); };
      img.src = reader.result;
      this.onChange(true);
    };
    reader.readAsDataURL(f);
  }

  // Bitmaps can come from code too (tests, examples): base64 of a PNG.
  setBitmap(b64) { this.bitmap = b64; this.setKind('bitmap'); }

  paint() {
    const c = this.canvas, ctx = c.getContext('2d');
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, c.width, c.height);
    ctx.strokeStyle = '#eee'; ctx.lineWidth = 1;
    for (let i = 0; i <= c.width; i += 23) {
      ctx.beginPath(); ctx.moveTo(i + 0.5, 0); ctx.lineTo(i + 0.5, c.height); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(0, i + 0.5); ctx.lineTo(c.width, i + 0.5); ctx.stroke();
    }
    if (this.axis) { // the axis of revolution
      ctx.strokeStyle = '#c2632b'; ctx.setLineDash([6, 4]);
      ctx.beginPath(); ctx.moveTo(AXIS_X + 0.5, 0); ctx.lineTo(AXIS_X + 0.5, c.height); ctx.stroke();
      ctx.setLineDash([]);
    } else {
      ctx.strokeStyle = '#ccc';
      ctx.beginPath(); ctx.moveTo(c.width / 2, c.height / 2 - 6); ctx.lineTo(c.width / 2, c.height / 2 + 6);
      ctx.moveTo(c.width / 2 - 6, c.height / 2); ctx.lineTo(c.width / 2 + 6, c.height / 2); ctx.stroke();
    }
    ctx.lineWidth = 2; ctx.lineJoin = 'round';
    for (const pl of this.polylines) {
      if (!pl.points.length) continue;
      ctx.strokeStyle = pl === this.current ? '#c2632b' : '#222';
      ctx.beginPath(); ctx.moveTo(...pl.points[0]);
      for (const p of pl.points.slice(1)) ctx.lineTo(...p);
      if (pl.closed) ctx.closePath();
      ctx.stroke();
    }
  }

  // The page's JSON for this source; drawings in y-up drawing units (canvas pixels).
  spec() {
    if (this.kind === 'expr') return {kind: 'expr', text: this.text.value};
    if (this.kind === 'bitmap') return {kind: 'bitmap', data: this.bitmap || ''};
    const H = this.canvas.height;
    return {
      kind: 'drawn',
      polylines: this.polylines.filter((pl) => pl.points.length >= 2).map((pl) => ({
        points: pl.points.map(([x, y]) => [Math.round(x * 10) / 10, Math.round((H - y) * 10) / 10]),
        closed: pl.closed,
      })),
    };
  }

  axisX() { return AXIS_X; }
}

// A spine drawn in top view (x right, y up), lifted by `rise` pixels along its length.
export class SpineDrawing {
  constructor(canvas, {onChange}) {
    this.canvas = canvas; this.onChange = onChange; this.points = [];
    let down = false;
    canvas.addEventListener('pointerdown', (e) => {
      canvas.setPointerCapture(e.pointerId); down = true; this.points = [canvasPoint(canvas, e)]; this.paint();
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!down) return;
      const p = canvasPoint(canvas, e), q = this.points[this.points.length - 1];
      if (Math.hypot(p[0] - q[0], p[1] - q[1]) >= 3) { this.points.push(p); this.paint(); }
    });
    const up = () => { if (down) { down = false; this.paint(); this.onChange(true); } };
    canvas.addEventListener('pointerup', up);
    canvas.addEventListener('pointercancel', up);
    this.paint();
  }

  clear() { this.points = []; this.paint(); }

  paint() {
    const c = this.canvas, ctx = c.getContext('2d');
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, c.width, c.height);
    if (this.points.length < 2) return;
    ctx.strokeStyle = '#222'; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.moveTo(...this.points[0]);
    for (const p of this.points.slice(1)) ctx.lineTo(...p);
    ctx.stroke();
  }

  spec(rise, closed) {
    const H = this.canvas.height;
    let total = 0;
    const s = [0];
    for (let i = 1; i < this.points.length; i++) {
      total += Math.hypot(this.points[i][0] - this.points[i - 1][0], this.points[i][1] - this.points[i - 1][1]);
      s.push(total);
    }
    const pts = this.points.map(([x, y], i) => [x / 100, (H - y) / 100, total ? (rise * s[i] / total) / 100 : 0]);
    if (closed && pts.length > 2) pts.push(pts[0].slice());
    return {kind: 'drawn', points: pts.map((p) => p.map((v) => Math.round(v * 1000) / 1000)), closed: !!closed};
  }
}

// Foci placed by clicking on a side view (x across, z up), each with a weight.
export class FociInput {
  constructor(canvas, list, {onChange}) {
    this.canvas = canvas; this.list = list; this.onChange = onChange;
    this.foci = [{x: 0, z: -0.5, w: 1}, {x: 0, z: 0.5, w: 2}];
    canvas.addEventListener('click', (e) => {
      const [px, py] = canvasPoint(canvas, e);
      this.foci.push({x: Math.round((px - 150) / 5) / 10, z: Math.round((150 - py) / 5) / 10, w: 1});
      this.render(); this.onChange(true);
    });
    this.render();
  }

  clear() { this.foci = []; this.render(); }

  render() {
    const c = this.canvas, ctx = c.getContext('2d');
    ctx.fillStyle = '#fff'; ctx.fillRect(0, 0, c.width, c.height);
    ctx.strokeStyle = '#eee';
    for (let i = 0; i <= 300; i += 25) {
      ctx.beginPath(); ctx.moveTo(i + 0.5, 0); ctx.lineTo(i + 0.5, 300); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(0, i + 0.5); ctx.lineTo(300, i + 0.5); ctx.stroke();
    }
    this.foci.forEach((f, i) => {
      const x = 150 + f.x * 50, y = 150 - f.z * 50, r = 3 + 3 * Math.sqrt(f.w);
      ctx.fillStyle = '#c2632b'; ctx.beginPath(); ctx.arc(x, y, r, 0, 2 * Math.PI); ctx.fill();
      ctx.fillStyle = '#222'; ctx.font = '12px sans-serif'; ctx.fillText(`${i + 1}`, x + r + 2, y - r);
    });
    this.list.replaceChildren(...this.foci.map((f, i) => {
      const w = el('input', {type: 'number', value: String(f.w), min: '0.1', step: '0.1', class: 'weight'});
      w.addEventListener('change', () => { f.w = Number(w.value); this.render(); this.onChange(true); });
      const rm = el('button', {type: 'button'}, '×');
      rm.addEventListener('click', () => { this.foci.splice(i, 1); this.render(); this.onChange(true); });
      return el('div', {class: 'row'}, `focus ${i + 1} at (${f.x}, 0, ${f.z}) weight `, w, rm);
    }));
  }

  spec() {
    return {foci: this.foci.map((f) => [f.x, 0, f.z]), weights: this.foci.map((f) => f.w)};
  }
}
