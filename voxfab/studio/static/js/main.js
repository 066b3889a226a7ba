// voxfab studio: wiring of the tabs, the shape being worked on, and the server calls.

import {Cancelled, cancelJob, fileUrl, get, post, saveBlob, waitJob, waitingJobs} from './api.js';
import {CurveSource, FociInput, SPINES, SpineDrawing} from './draw.js';
import {LayerEditor} from './editor.js';
import {MakerForms} from './makers.js';
import {carryEdits, Grid} from './grid.js';
import {drawThumb} from './nets.js';
import {NetView} from './netview.js';
import {faceFills, PaintPanel} from './paint.js';
import {placedLayout, SheetBoard} from './sheets.js';
import {Viewer} from './viewer.js';

const $ = (sel) => document.querySelector(sel);
const $$ = (sel) => [...document.querySelectorAll(sel)];

const state = {
  shape: new Grid(), // the current 25³ shape
  drawn: null, // the drawing that made it, while unedited (for the recipe)
  base: null, // the drawing's own shape (the last preview): hand edits are what differs from it
  baseMaker: null, // the maker of that drawing: hand edits on one maker's shape do not go onto another's
  opened: false, // the shape came from the repository or the command line, not from the drawing
  parked: null, // {shape, base, maker}: hand edits set aside while the drawing has an error
  stroking: false, // a stroke is being drawn: its previews after the first add no undo step
  edited: false,
  name: null, // repository name once saved
  label: null, // what the shape was opened as (a file's name without its extension), for file names
  gallery: null, // {job, nets}
  chosen: null, // index of the chosen net in the gallery
};

// --- messages and progress ---------------------------------------------------------------------

// Say what happened in the status line; an error from the server keeps its technical line as a tooltip.
function say(text, info = false) {
  const m = $('#message');
  const detail = text instanceof Error ? text.detail || '' : '';
  if (text instanceof Error) text = text.message;
  m.textContent = text; m.classList.toggle('info', info);
  if (detail) m.title = detail; else m.removeAttribute('title');
}

// A job's progress in the status line: its place in the queue while it waits, then done of total.
function progress(done, total, text, status = null) {
  const queued = status && status.state === 'queued';
  $('#progress').classList.remove('hidden');
  $('#progress').dataset.state = status ? status.state : 'running';
  $('#progress').dataset.place = String(status ? status.place || 0 : 0);
  $('#progress-bar').style.width = queued ? '0px' : `${Math.round(300 * done / Math.max(total, 1))}px`;
  $('#progress-text').textContent = queued || !total || total <= 1 ? text || '' : `${text || ''} (${done} of ${total})`;
}

function progressDone() { $('#progress').classList.add('hidden'); delete $('#progress').dataset.state; }

$('#job-cancel').addEventListener('click', async () => {
  $('#progress-text').textContent = 'cancelling…';
  for (const id of waitingJobs()) await cancelJob(id).catch(() => {});
});

// --- the shape and its facts --------------------------------------------------------------------

const viewer = new Viewer($('#viewer'));

const NO_FACTS = {volume: 0, extents: [0, 0, 0], well_formed: false, reasons: [], none: true};

function showFacts(f) {
  const wf = $('#wf');
  // no shape (the drawing has an error): neither a green nor a red badge over a shape that is not there
  wf.textContent = f.none ? 'no shape' : f.well_formed ? 'well formed' : 'not well formed';
  wf.className = `badge ${f.none ? '' : f.well_formed ? 'ok' : 'bad'}`;
  wf.dataset.wellFormed = String(f.well_formed);
  $('#volume').textContent = f.none ? '' : `${f.volume} voxels · ${f.extents.join('×')}`;
  $('#volume').dataset.volume = String(f.volume);
  $('#reasons').replaceChildren(...f.reasons.map((r, i) => {
    const li = Object.assign(document.createElement('li'), {textContent: r});
    if (f.terms && f.terms[i] && f.terms[i] !== r) li.title = f.terms[i]; // the technical words, on hover
    return li;
  }));
}

// What belonged to the shape before it changed: its saved name's note, its nets and the marks on them.
function forgetShapeState() {
  $('#save-result').textContent = ''; delete $('#save-result').dataset.name;
  forgetNet();
  clearAnswers();
  if (marker.marks && (marker.marks.cut.length || marker.marks.keep.length)) marker.clear();
}

function setShape(grid, facts, {drawn = null, name = null, label = null, keepHistory = false} = {}) {
  state.shape = grid; state.drawn = drawn; state.edited = false; state.name = name; state.label = label;
  forgetShapeState();
  $('#shape-name').textContent = name || 'unsaved';
  viewer.stop();
  viewer.setGrid(grid, currentTab() === 'edit' ? editor.layer : null);
  editor.setGrid(grid, {keepHistory}); paint.refresh();
  showFacts(facts);
  recipeNote();
  netNote();
}

// What the page knows of the shape besides its voxels, kept with each undo step and restored with it: the
// drawing's shape and maker (hand edits are what differs from it) and the names it was opened or saved under.
function shapeTag() {
  return {base: state.base, maker: state.baseMaker, name: state.name, label: state.label,
    heading: $('#shape-name').textContent};
}

// A new preview of the drawing: hand edits are kept on it, and a shape it replaces stays one Undo away.
// `remember`: false for the previews of a stroke after its first, so that one stroke is one undo step.
function drawingChanged(fresh, facts, spec, remember = true) {
  const before = state.shape, beforeBase = state.base, was = shapeTag();
  // the edits on the shape now, or those set aside while the drawing had an error
  const carry = state.edited && beforeBase ? {shape: before, base: beforeBase, maker: state.baseMaker} : state.parked;
  state.parked = null;
  if (carry && carry.maker !== spec.maker) {
    // Another maker: voxels edited on its shape (the egg) mean nothing on this one's (the vase). This shape
    // starts clean; the edited one stays one Undo away.
    const n = carryEdits(carry.base, carry.shape, carry.base)[1];
    state.base = fresh.clone(); state.baseMaker = spec.maker; state.opened = false;
    if (remember) editor.remember(before, was);
    setShape(fresh, facts, {drawn: spec, keepHistory: true});
    say(`A new maker (${makers.label(spec.maker)}): its shape starts clean; your ${n} hand-edited voxel${n === 1 ? ' stays' : 's stay'} `
      + `on the ${makers.label(carry.maker)} shape (Undo in Edit brings it back).`, true);
    return;
  }
  if (carry) {
    // the drawing still gives the same shape: the edits stand as they are
    if (carry.shape === before && carry.base.equals(fresh)) return;
    const [kept, n] = carryEdits(carry.base, carry.shape, fresh);
    state.base = fresh; state.baseMaker = spec.maker;
    if (remember) editor.remember(before, was);
    setShape(kept, facts, {keepHistory: true});
    state.edited = true; $('#shape-name').textContent = 'unsaved';
    check();
    say(`The drawing changed: your ${n} hand-edited voxel${n === 1 ? ' is' : 's are'} kept on the new shape (Undo in Edit goes back).`, true);
    return;
  }
  const replacing = (state.opened || state.edited) && before.count() > 0;
  state.base = fresh.clone(); state.baseMaker = spec.maker; state.opened = false;
  if (replacing && remember) editor.remember(before, was);
  setShape(fresh, facts, {drawn: spec, keepHistory: replacing});
  if (replacing) say('The drawing replaced the opened shape (Undo in Edit brings it back).', true);
}

// The drawing cannot make a shape: show none rather than the last one under its old badge.
function drawingFailed(remember = true) {
  if (state.shape.count() === 0 && !state.edited) { showFacts(NO_FACTS); viewer.setGrid(state.shape); return; }
  const before = state.shape, beforeBase = state.base, was = shapeTag();
  // back when it is fixed
  if (state.edited && beforeBase) state.parked = {shape: before.clone(), base: beforeBase, maker: state.baseMaker};
  state.base = null; state.baseMaker = null;
  if (remember) editor.remember(before, was);
  setShape(new Grid(), NO_FACTS, {keepHistory: true});
}

// --- Draw ---------------------------------------------------------------------------------------

let inFlight = false, pending = null;

function schedule(final) {
  pending = {final, t: performance.now()};
  if (!inFlight) runPreview();
}

function drawnEmpty(src) {
  return (src.kind === 'drawn' && !src.polylines.some((p) => p.points.length >= 2)) || (src.kind === 'bitmap' && !src.bitmap);
}

function currentSpec() {
  const maker = $('#maker').value;
  const spec = {maker};
  // the top row's walls and inside, for a maker that takes them
  if (makers.takes('k')) spec.k = Number($('#k').value);
  if (makers.takes('mode')) spec.mode = $('#mode').value;
  if (maker === 'revolution') {
    spec.curve = sources.curve.spec(); spec.generatrix = sources.generatrix.spec();
    if (spec.generatrix.kind === 'drawn') spec.axis = sources.generatrix.axisX();
    if (spec.generatrix.kind === 'expr' && /^\s*x\s*=[^=]/.test(spec.generatrix.text)) {
      spec.z_range = [Number($('#z-lo').value), Number($('#z-hi').value)];
    }
  } else if (maker === 'tube') {
    spec.profile = sources.profile.spec();
    if ($('input[name=spine-kind]:checked').value === 'expr') {
      spec.spine = {kind: 'expr', x: $('#spine-x').value, y: $('#spine-y').value, z: $('#spine-z').value};
    } else {
      spec.spine = spine.spec(Number($('#spine-rise').value), $('#spine-closed').checked);
    }
    spec.frame = $('#frame').value; spec.radius = Number($('#radius').value); spec.twist = Number($('#twist').value);
  } else if (maker === 'focal') {
    Object.assign(spec, foci.spec(), {radius: Number($('#focal-radius').value)});
  } else if (maker === 'implicit') {
    spec.expression = $('#implicit-expression').value;
  }
  if (makers.drawn('arc') && $('#arc-open').checked) {
    spec.arc = [Number($('#arc-start').value), Number($('#arc-end').value)];
  }
  // the maker's other keys, from the form its row generates
  return Object.assign(spec, makers.values());
}

function emptyDrawing(spec) {
  if (spec.maker === 'revolution') {
    return drawnEmpty(sources.curve) ? 'curve of revolution' : drawnEmpty(sources.generatrix) ? 'generatrix' : null;
  }
  if (spec.maker === 'tube') {
    if (drawnEmpty(sources.profile)) return 'profile';
    if (spec.spine.kind === 'drawn' && spec.spine.points.length < 2) return 'spine';
  }
  if (spec.maker === 'focal' && !spec.foci.length) return 'foci';
  return null;
}

async function runPreview() {
  const req = pending; pending = null;
  const spec = currentSpec();
  const missing = emptyDrawing(spec);
  // The first preview of a stroke keeps the shape before it one Undo away; the stroke's later
  // previews (and its last, on release) replace that preview without a step of their own.
  const remember = !state.stroking;
  state.stroking = !req.final;
  // an unfinished drawing has no shape yet: none is shown rather than the last one
  if (missing) { say(`Draw or choose the ${missing} to see the shape.`, true); drawingFailed(remember); return; }
  inFlight = true;
  try {
    const r = await post('/api/preview', spec);
    say('');
    drawingChanged(Grid.unpack(r.grid), r.facts, spec, remember);
    const ms = performance.now() - req.t;
    const lat = $('#latency');
    lat.textContent = `preview ${Math.round(ms)} ms (digitizing ${Math.round(r.ms)} ms)`;
    if (req.final) { lat.dataset.ms = String(Math.round(ms)); lat.dataset.count = String(Number(lat.dataset.count || 0) + 1); }
  } catch (e) {
    say(e);
    drawingFailed(remember);
  } finally {
    inFlight = false;
    if (pending) runPreview();
  }
}

const sources = {
  curve: new CurveSource($('#src-curve'), {expr: 'x^2 + y^2 = 1', onChange: schedule}),
  generatrix: new CurveSource($('#src-generatrix'), {expr: 'x = 0.6 + 0.3*sin(3*y)', onChange: schedule, axis: true}),
  profile: new CurveSource($('#src-profile'), {
    expr: 'min((x - 0.5)^2 + y^2 - 0.2, (x + 0.5)^2 + y^2 - 0.2)', onChange: schedule}),
};
const spine = new SpineDrawing($('#spine-canvas'), {onChange: schedule});
const foci = new FociInput($('#foci-canvas'), $('#foci-list'), {onChange: schedule});

// The keys of a maker that the page has controls of its own for, beside its drawing's: the top row's walls
// and inside, the tube's frames, radius and twist. Its other keys get fields from the makers table.
const OWN_CONTROLS = {tube: ['frame', 'radius', 'twist']};
const makers = new MakerForms($('#maker'), $('#maker-form'), {
  own: (maker) => ['k', 'mode', ...(OWN_CONTROLS[maker] || [])], onChange: () => schedule(true)});

// The chosen maker's drawing (none for a maker the page has no drawing for), its top-row controls and its form.
function showMaker() {
  const maker = $('#maker').value;
  for (const d of $$('#pane-draw .maker')) d.classList.toggle('hidden', d.id !== `maker-${maker}`);
  $('label:has(#k)').classList.toggle('hidden', !makers.takes('k'));
  $('label:has(#mode)').classList.toggle('hidden', !makers.takes('mode'));
  for (const l of $$('label:has(#arc-open), label:has(#arc-end)')) l.classList.toggle('hidden', !makers.drawn('arc'));
  makers.show();
}
$('#maker').addEventListener('change', () => { showMaker(); schedule(true); });
for (const id of ['#k', '#mode', '#arc-open', '#arc-start', '#arc-end', '#z-lo', '#z-hi', '#frame', '#radius', '#twist', '#spine-x', '#spine-y', '#spine-z',
  '#focal-radius', '#spine-rise', '#spine-closed', '#implicit-expression']) {
  $(id).addEventListener('change', () => schedule(true));
}
$$('input[name=spine-kind]').forEach((r) => r.addEventListener('change', () => {
  const drawn = $('input[name=spine-kind]:checked').value === 'drawn';
  $('#spine-expr').classList.toggle('hidden', drawn); $('#spine-drawn').classList.toggle('hidden', !drawn);
  schedule(true);
}));
$('#spine-preset').addEventListener('change', () => {
  const [x, y, z] = SPINES[$('#spine-preset').value];
  $('#spine-x').value = x; $('#spine-y').value = y; $('#spine-z').value = z;
  schedule(true);
});
$('#spine-clear').addEventListener('click', () => spine.clear());
$('#foci-clear').addEventListener('click', () => { foci.clear(); schedule(true); });

$('#play').addEventListener('click', async () => {
  $('#anim-status').textContent = 'computing frames…';
  try {
    const r = await post('/api/animate', {shape: currentSpec(), steps: 24});
    viewer.play(r.frames.map(Grid.unpack));
    $('#anim-status').textContent = `${r.frames.length} frames`;
    $('#anim-status').dataset.frames = String(r.frames.length);
  } catch (e) { $('#anim-status').textContent = ''; say(e); }
});
$('#stop').addEventListener('click', () => { viewer.stop(); viewer.setGrid(state.shape); $('#anim-status').textContent = ''; });

// --- Edit ---------------------------------------------------------------------------------------

let checking = false, recheck = false;

async function check() {
  if (checking) { recheck = true; return; }
  checking = true;
  try {
    const r = await post('/api/check', {grid: state.shape.pack()});
    showFacts(r.facts);
  } catch (e) { say(e); } finally {
    checking = false;
    if (recheck) { recheck = false; check(); }
  }
}

function edited() {
  state.edited = true; state.drawn = null; state.name = null; state.parked = null;
  forgetShapeState();
  $('#shape-name').textContent = 'unsaved';
  viewer.setGrid(state.shape, editor.layer); paint.refresh();
  recipeNote(); netNote();
  check();
}

const editor = new LayerEditor($('#layer-canvas'), {onEdit: () => edited(), tag: shapeTag, pen: (g) => paint.pen(g)});
const paint = new PaintPanel({editor, viewer, say, title: () => shapeTitle(), pitch: () => Number($('#pitch').value), // a file opened: as a kept shape
  opened: (r) => { openShape(null, r); $('#shape-name').textContent = r.label; if (r.pitch) $('#pitch').value = String(r.pitch); }});

function setLayer(z) {
  editor.setLayer(z);
  $('#layer').value = String(editor.layer); $('#layer-out').textContent = String(editor.layer);
  viewer.setLayer(editor.layer);
}
$('#layer').addEventListener('input', () => setLayer(Number($('#layer').value)));
$('#layer-up').addEventListener('click', () => setLayer(editor.layer + 1));
$('#layer-down').addEventListener('click', () => setLayer(editor.layer - 1));
// Undo and redo also step back over a drawing change, a refused drawing or an opened shape: the base and
// its maker go with the shape, and so do the names the shape had (an opened file, a kept shape), for its files.
function stepped() {
  const t = editor.tag || {};
  state.base = t.base || null; state.baseMaker = t.maker || null;
  edited();
  if (t.name || t.label) {
    state.name = t.name; state.label = t.label; $('#shape-name').textContent = t.heading;
  }
}
function undo() { if (editor.undo()) stepped(); else say('Nothing to undo.', true); }
function redo() { if (editor.redo()) stepped(); else say('Nothing to redo.', true); }
$('#undo').addEventListener('click', undo);
$('#redo').addEventListener('click', redo);
$('#clear-layer').addEventListener('click', () => { editor.clearLayer(); edited(); });
$('#fill-layer').addEventListener('click', () => { editor.copyBelow(); edited(); });
document.addEventListener('keydown', (e) => {
  if (currentTab() !== 'edit' || !(e.ctrlKey || e.metaKey)) return;
  if (e.key === 'z' && !e.shiftKey) { e.preventDefault(); undo(); }
  if (e.key === 'y' || (e.key === 'z' && e.shiftKey)) { e.preventDefault(); redo(); }
});

// --- Keep ---------------------------------------------------------------------------------------

function recipeNote() {
  $('#recipe-note').textContent = state.drawn ? ''
    : 'The recipe describes a drawn shape: this one was edited by hand or opened from the repository, so keep it in the repository instead.';
  $('#save-recipe').disabled = !state.drawn;
  // the animation turns a drawn tube's profile: no other shape has one
  const tube = Boolean(state.drawn && state.drawn.maker === 'tube');
  for (const b of $$('[data-make="animation.gif"]')) b.classList.toggle('hidden', !tube);
}

$('#save-repo').addEventListener('click', async () => {
  try {
    const r = await post('/api/repo', {grid: state.shape.pack(), draft: $('#save-draft').checked});
    state.name = r.name;
    $('#shape-name').textContent = r.name;
    const text = (r.draft ? `Kept as draft ${r.name}: ${r.reasons.join('; ')}`
      : r.created ? `Saved as ${r.name}` : `Already in the repository as ${r.name}`);
    $('#save-result').textContent = text; $('#save-result').dataset.name = r.name;
    say(text, true);
    refreshRepo();
  } catch (e) { $('#save-result').textContent = ''; say(e); }
});

$('#save-recipe').addEventListener('click', async () => {
  try {
    const resp = await fetch('/api/recipe', {method: 'POST', headers: {'Content-Type': 'application/json'},
      body: JSON.stringify({shape: state.drawn, name: $('#recipe-name').value, pitch: Number($('#pitch').value)})});
    if (!resp.ok) throw new Error((await resp.json()).error);
    const name = /filename="([^"]+)"/.exec(resp.headers.get('content-disposition'))[1];
    saveBlob(await resp.blob(), name);
    say(`Recipe saved as ${name}: voxfab build ${name.replace('.zip', '/…toml')} makes this shape.`, true);
  } catch (e) { say(e); }
});

async function refreshRepo(after = null) {
  try {
    const r = await get(after ? `/api/repo?after=${encodeURIComponent(after)}` : '/api/repo');
    const figures = r.shapes.map((s) => {
      const fig = document.createElement('figure');
      fig.dataset.name = s.name;
      const img = Object.assign(document.createElement('img'), {src: `/api/repo/thumb?name=${encodeURIComponent(s.name)}`,
        alt: s.name, loading: 'lazy'});
      const cap = Object.assign(document.createElement('figcaption'), {textContent: `${s.name} · ${s.volume}`});
      fig.append(img, cap);
      fig.addEventListener('click', () => openShape(s.name));
      return fig;
    });
    // a page at a time: a repository may hold many thousands of shapes
    if (after) $('#repo-grid').append(...figures); else $('#repo-grid').replaceChildren(...figures);
    $('#repo-more').classList.toggle('hidden', !r.more);
    $('#repo-more').dataset.after = r.shapes.length ? r.shapes[r.shapes.length - 1].name : '';
  } catch (e) { say(e); }
}
$('#repo-refresh').addEventListener('click', () => refreshRepo());
$('#repo-more').addEventListener('click', () => refreshRepo($('#repo-more').dataset.after));

async function openShape(name, file = null) { // a kept shape by name, or a file the page opened (paint.js)
  try {
    const r = file || await get(`/api/repo/shape?name=${encodeURIComponent(name)}`);
    const before = state.shape, was = shapeTag();
    state.base = null; state.baseMaker = null; state.opened = true;
    editor.remember(before, was); // Undo in Edit returns to the shape it replaced, under its name
    setShape(Grid.unpack(r.grid), r.facts, {name, label: file && file.label.replace(/\.[A-Za-z0-9]+$/, ''), keepHistory: true});
    if (!file) say(`Opened ${name}`, true);
  } catch (e) { say(e); }
}

// --- Net ----------------------------------------------------------------------------------------

const marker = new NetView($('#net-canvas'), {viewer, shape: () => state.shape, say, fold: $('#net-fold'), play: $('#net-fold-play'), undo: $('#net-undo'),
  pieces: $('#net-view-pieces'), placement: () => (state.gallery && state.chosen !== null ? state.gallery.placement : null),
  onChange: () => {
  const c = marker.constraints();
  $('#marks-count').textContent = `${c.cut.length} cut, ${c.keep.length} kept`;
  $('#marks-count').dataset.constraints = JSON.stringify(c);
  // An edit makes a new net: its pieces go on the sheets as the server placed them, and its files follow.
  const g = state.gallery, edited = marker.item;
  if (g && state.chosen !== null && edited && edited.job === marker.job && edited.placement) {
    g.placement = edited.placement; g.layout = edited.layout;
    board.setNet(edited.layout, edited.placement);
    makeNetFiles();
  }
}});

const board = new SheetBoard($('#net-sheets'), {
  onChange: (placement) => {
    const g = state.gallery;
    if (!g || state.chosen === null) return;
    g.placement = placement;
    // Moves and turns in quick succession make one set of files, for the last layout.
    clearNetFiles();
    clearTimeout(netFiles.timer);
    netFiles.timer = setTimeout(makeNetFiles, 400);
  },
  onSelect: (q) => { $('#piece-chosen').textContent = q === null ? '' : `piece (${q + 1}) chosen`; },
});
$('#piece-turn').addEventListener('click', () => board.turn());

// The CLI's words without its flags: the artist reads what to do, the flag stays in the CLI.
function plainWords(text) {
  return text.replace(/,?\s*CLI --pieces auto/g, '').replace(/\(pieces='auto'\)/g, '(split into pieces)')
    .replace(/\s*\(--[a-z-]+(?: [A-Za-z0-9.]+)?\)/g, '').replace(/--pieces auto/g, 'split into pieces')
    .replace(/--no-numbers/g, 'no seam labels').replace(/--no-tabs/g, 'no glue tabs').replace(/--([a-z-]+)/g, '$1');
}

function sayError(e) {
  const err = new Error(plainWords(e.message || String(e)));
  err.detail = e.detail || '';
  say(err);
}

function sheetValue() {
  return $('#net-sheet').value === 'custom' ? $('#net-sheet-custom').value.trim() : $('#net-sheet').value;
}

// The net options as the net output names them (NetOptions / DrawingOptions fields).
function netOptions() {
  const face = $('#net-face').value;
  return {sheet: sheetValue(), face_size: face ? Number(face) : null, pieces: $('#net-pieces').value,
    numbers: $('#net-numbers').checked, tabs: $('#net-tabs').checked, fill: $('#net-fill').checked,
    compact: $('#net-compact').checked,
    timeout: Number($('#net-timeout').value)};
}

function fillSheets(sheets) {
  const sel = $('#net-sheet');
  sel.replaceChildren(...Object.entries(sheets).map(([name, [w, h]]) =>
    Object.assign(document.createElement('option'), {value: name, textContent: `${name} (${w} × ${h} mm)`})),
  Object.assign(document.createElement('option'), {value: 'custom', textContent: 'custom size (laser bed)…'}));
  sel.value = 'A4';
}
$('#net-sheet').addEventListener('change', () => {
  $('#net-sheet-custom-box').classList.toggle('hidden', $('#net-sheet').value !== 'custom');
});

const netFiles = {generation: 0}; // bumped whenever the chosen net or its layout changes

function clearNetFiles() {
  netFiles.generation++;
  for (const a of $$('#net-files a')) { a.removeAttribute('href'); a.removeAttribute('download'); a.dataset.state = 'none'; }
}

// A new search: the last gallery's summary, chosen net, sheets and files go (none is left to edit or cut).
function forgetNet() {
  state.gallery = null; state.chosen = null;
  $('#net-summary').textContent = ''; delete $('#net-summary').dataset.found; delete $('#net-summary').dataset.seconds;
  $('#net-chosen-label').textContent = ''; delete $('#net-chosen-label').dataset.index;
  marker.setLayout(null);
  netNote();
}

function netNote() {
  const g = state.gallery;
  $('#make-net').textContent = g && state.chosen !== null
    ? `Net files use net ${state.chosen + 1} of the gallery (seed ${g.nets[state.chosen].seed}), as laid out in Net.`
    : 'Net files use a new net (seed 0) unless you pick one in Net.';
  if (!g) {
    $('#net-gallery').replaceChildren(); $('#net-chosen-label').textContent = '';
    board.setNet(null, null); clearNetFiles();
  }
}

// The Net tab's control of each net option a way out may set (the sheet has its own two).
const NET_CONTROLS = {pieces: '#net-pieces', face_size: '#net-face', numbers: '#net-numbers', tabs: '#net-tabs',
  fill: '#net-fill', compact: '#net-compact', timeout: '#net-timeout'};

// Set every option of `options` ({name: value}, as netOptions() names them) on the Net tab's controls.
function setNetOptions(options) {
  for (const [name, value] of Object.entries(options)) {
    if (name === 'sheet') {
      const known = [...$('#net-sheet').options].some((x) => x.value === value);
      $('#net-sheet').value = known ? value : 'custom';
      if (!known) $('#net-sheet-custom').value = value;
      $('#net-sheet').dispatchEvent(new Event('change'));
      continue;
    }
    const control = NET_CONTROLS[name] && $(NET_CONTROLS[name]);
    if (!control) throw new Error(`this way out sets ${name}, which the page has no control for`);
    if (control.type === 'checkbox') control.checked = Boolean(value);
    else control.value = value === null ? '' : String(value);
  }
}

// One button per way out of a net that does not fit: it sets all its options and searches again.
// A new question of the Net tab (a gallery, "does one piece fit?"): the last answer and its ways out go,
// so that the answer on screen is always the latest one's.
function clearAnswers() {
  const out = $('#net-fits-answer');
  out.textContent = ''; delete out.dataset.answer; out.removeAttribute('title');
  showWaysOut([]);
}

function showWaysOut(ways) {
  $('#net-ways').replaceChildren(...(ways || []).map((w) => {
    const b = Object.assign(document.createElement('button'), {type: 'button', textContent: w.label});
    b.dataset.options = JSON.stringify(w.options);
    b.addEventListener('click', () => {
      try { setNetOptions(w.options); } catch (e) { say(e.message); return; }
      gallery(false);
    });
    return b;
  }));
}

// "1 net in pieces", "8 nets in pieces", "8 nets, each different once cut out".
function galleryWords(found, inPieces) {
  const nets = found === 1 ? 'net' : 'nets';
  return inPieces ? `${nets} in pieces` : found === 1 ? 'net' : `${nets}, each different once cut out`;
}

// One figure of the gallery: net i on its sheets, with how it fits; a click chooses it.
function galleryFigure(n, i) {
  const fig = document.createElement('figure');
  fig.dataset.testid = 'net-gallery-item';
  fig.setAttribute('data-testid', 'net-gallery-item');
  fig.dataset.index = String(i);
  // the first sheet large, the others in a strip below it: every sheet squeezed into one row left faces a pixel wide
  const strip = n.placement && n.placement.sheets > 1;
  const cv = Object.assign(document.createElement('canvas'), {width: 420, height: strip ? 540 : 420});
  cv.dataset.facePx = drawThumb(cv, placedLayout(n.layout, n.placement), n.placement, faceFills(n.layout, state.shape)).toFixed(2);
  const f = n.fit;
  const cap = document.createElement('figcaption');
  cap.innerHTML = '<b></b> <span class="fits"></span>';
  cap.querySelector('b').textContent = `#${i + 1}`;
  cap.querySelector('span').textContent = f.fits
    ? `${n.pieces} piece${n.pieces > 1 ? 's' : ''} on ${f.sheets} sheet${f.sheets > 1 ? 's' : ''} ${f.sheet}, `
      + `faces ${f.face_size} mm`
    : `${n.pieces} piece${n.pieces > 1 ? 's' : ''}: does not fit ${f.sheet} at ${f.face_size} mm faces`;
  fig.append(cv, cap);
  fig.addEventListener('click', () => choose(i));
  return fig;
}

async function gallery(withMarks) {
  const options = netOptions();
  const body = {grid: state.shape.pack(), count: Number($('#net-count').value), seed: Number($('#net-seed').value),
    options, constraints: withMarks ? marker.constraints() : null};
  forgetNet(); clearAnswers();
  try {
    $('#net-go').disabled = true; $('#net-regen').disabled = true;
    const t0 = performance.now();
    const {job} = await post('/api/nets', body);
    $('#net-gallery').dataset.job = job;
    // a new gallery: nothing chosen yet; the marks stay (they name faces, not a net)
    $('#net-chosen-label').textContent = ''; delete $('#net-chosen-label').dataset.index;
    marker.setLayout(null);
    progress(0, body.count, 'searching nets');
    const g = {job, nets: [], options: {...options}, placement: null};
    // Each net is drawn as soon as the server has made it: the artist looks at (and may pick) the
    // first while the next is cut.
    const show = (items, from) => {
      state.gallery = g;
      items.forEach((n, k) => {
        g.nets.push(n);
        g.options.face_size = n.fit.face_size;
        const fig = galleryFigure(n, from + k);
        fig.dataset.ms = String(Math.round(performance.now() - t0));
        $('#net-gallery').append(fig);
      });
      netNote();
    };
    let s;
    try { s = await waitJob(job, progress, 150, show); } catch (e) {
      if (e instanceof Cancelled && g.nets.length) { // a cancelled gallery keeps the nets it showed, and says so
        const n = g.nets.length, kept = `Cancelled: ${n} net${n === 1 ? '' : 's'} kept`;
        $('#net-summary').textContent = `${kept} of the ${body.count} asked, faces ${g.options.face_size} mm.`;
        $('#net-summary').dataset.found = String(n);
        say(`${kept}: pick one to lay it out and make its files.`, true);
        return;
      }
      state.gallery = null; state.chosen = null; netNote();
      const st = await get(`/api/jobs/${job}`);
      showWaysOut(st.ways_out);
      throw e;
    }
    const r = s.result;
    if (g.nets.length < r.nets.length) show(r.nets.slice(g.nets.length), g.nets.length);
    g.options.face_size = r.options.face_size;
    const secs = ((performance.now() - t0) / 1000).toFixed(1);
    const what = galleryWords(r.found, r.nets.some((n) => n.pieces > 1));
    $('#net-summary').textContent = `${r.found} ${what} in ${secs} s, faces ${r.options.face_size} mm.`;
    $('#net-summary').dataset.found = String(r.found); $('#net-summary').dataset.seconds = secs;
    netNote();
    say(`${r.found} ${what}: pick one to lay it out and make its files.`, true);
  } catch (e) { sayError(e); } finally {
    progressDone(); $('#net-go').disabled = false; $('#net-regen').disabled = false;
  }
}

function choose(i) {
  const g = state.gallery;
  state.chosen = i; g.placement = g.nets[i].placement; g.layout = g.nets[i].layout;
  $$('#net-gallery figure').forEach((f, j) => f.classList.toggle('chosen', i === j));
  marker.setNet(g.job, i, g.nets[i].layout);
  board.setNet(g.nets[i].layout, g.placement);
  // a gallery's net is found again by its seed; the net that fits a sheet has no seed worth naming
  $('#net-chosen-label').textContent = g.fits ? `the one-piece net that fits ${g.fits}` : `#${i + 1} (seed ${g.nets[i].seed})`;
  $('#net-chosen-label').dataset.index = String(i);
  netNote();
  makeNetFiles();
}

// What the files are named after: the shape's repository name, the file it was opened from, or the
// recipe name of a drawn shape (characters a file name may not hold become '-').
function shapeTitle() {
  const title = state.name || state.label || $('#recipe-name').value || 'studio';
  return title.replace(/[^A-Za-z0-9_. -]/g, '-').slice(0, 64) || 'studio';
}

// The body of /api/make for a net file of the chosen net, as laid out on the sheets.
function netMakeBody(artefact) {
  const g = state.gallery;
  return {grid: state.shape.pack(), artefact, pitch: Number($('#pitch').value),
    title: shapeTitle(), options: g.options,
    net: {job: marker.job, index: marker.index}, placement: g.placement};
}

// Make the four net files of the chosen net as laid out; the links point at them once made.
async function makeNetFiles() {
  clearTimeout(netFiles.timer);
  clearNetFiles();
  const generation = netFiles.generation;
  const links = $$('#net-files a');
  links.forEach((a) => { a.dataset.state = 'making'; });
  say('making the net files of the sheets shown…', true);
  try {
    const made = await Promise.all(links.map(async (a) => {
      const {job} = await post('/api/make', netMakeBody(`net.${a.dataset.kind}`));
      const s = await waitJob(job);
      return {a, job, file: s.files[0]};
    }));
    if (generation !== netFiles.generation) return; // the layout changed meanwhile: newer files are coming
    for (const {a, job, file} of made) {
      a.href = fileUrl(job, file.index); a.download = file.name; a.dataset.state = 'ready';
      a.title = `${file.name} (${Math.ceil(file.bytes / 1024)} kB)`;
    }
    say(`Net files ready: ${made.map((m) => m.file.name).join(', ')}, as the sheets show.`, true);
  } catch (e) {
    if (generation !== netFiles.generation) return;
    links.forEach((a) => { a.dataset.state = 'error'; });
    sayError(e);
  }
}

$('#net-go').addEventListener('click', () => gallery(false));

// "Does one piece fit this sheet?": the exact strategy's yes (with the net), no (proved) or undecided.
$('#net-fits').addEventListener('click', async () => {
  const out = $('#net-fits-answer');
  clearAnswers();
  try {
    // the options the question reads: one piece, cavities filled, so pieces, fill and compact are the gallery's
    const {sheet, face_size, numbers, tabs, timeout} = netOptions();
    const {job} = await post('/api/fits', {grid: state.shape.pack(), options: {sheet, face_size, numbers, tabs, timeout}});
    const s = await waitJob(job, progress);
    progressDone();
    const r = s.result;
    out.textContent = r.message; out.dataset.answer = r.answer;
    if (r.detail) out.title = r.detail; else out.removeAttribute('title');
    if (r.answer === 'yes' && r.net) openFound(job, r);
    say(r.message, true);
  } catch (e) { progressDone(); sayError(e); }
});

// A "yes": the net the search found becomes the chosen net, in the editor and on the sheets, with its files.
function openFound(job, r) {
  forgetNet(); showWaysOut([]);
  state.gallery = {job, nets: [r.net], options: {...netOptions(), face_size: r.face_size}, placement: null,
    fits: `${r.sheet} at ${r.face_size} mm faces`};
  $('#net-gallery').replaceChildren();
  $('#net-summary').textContent = `The one-piece net found for ${r.sheet} at ${r.face_size} mm faces is open below.`;
  choose(0);
}
$('#net-regen').addEventListener('click', () => gallery(true));
$('#marks-clear').addEventListener('click', () => marker.clear());

// --- Make ---------------------------------------------------------------------------------------

// The options of the artefact's own output only: the server refuses an option that would have no effect.
function makeOptions(artefact) {
  if (artefact.startsWith('net.')) return netOptions();
  if (artefact === 'plates.zip') {
    return {thickness: Number($('#thickness').value), style: $('#plate-style').value, plate_sheet: $('#plate-sheet').value};
  }
  return {};
}

async function make(artefact) {
  const g = state.gallery;
  const chosen = g && state.chosen !== null && artefact.startsWith('net.');
  const body = chosen ? netMakeBody(artefact) : {grid: state.shape.pack(), artefact, pitch: Number($('#pitch').value),
    title: shapeTitle(),
    options: makeOptions(artefact),
    // only the net's files and the triptych are drawn from the chosen net
    net: g && state.chosen !== null && /^(net|triptych)\./.test(artefact) ? {job: marker.job, index: marker.index} : null,
    shape: artefact === 'animation.gif' ? state.drawn : undefined};
  try {
    const {job} = await post('/api/make', body);
    progress(0, 1, `making ${artefact}`);
    const s = await waitJob(job, progress);
    for (const f of s.files) {
      const a = Object.assign(document.createElement('a'), {href: fileUrl(job, f.index), download: f.name,
        textContent: `${f.name} (${Math.ceil(f.bytes / 1024)} kB)`});
      a.dataset.artefact = artefact;
      const li = document.createElement('li'); li.append(a);
      $('#downloads').prepend(li);
      a.click();
    }
    if (s.result && s.result.assembly) viewer.setMesh(s.result.assembly.plates);
    say(`${artefact}: ${s.files.map((f) => f.name).join(', ')} in ${s.seconds.toFixed(1)} s`, true);
  } catch (e) { sayError(e); } finally { progressDone(); }
}
// The Make buttons are the studio downloads of the table of outputs (the server's /api/info).
const MAKE_LABELS = {'plates.zip': 'Plates', 'animation.gif': 'Tube animation GIF'};
function makeLabel(name) {
  const [stem, ext] = name.split('.');
  return MAKE_LABELS[name] || `${stem[0].toUpperCase()}${stem.slice(1)} ${ext.toUpperCase()}`;
}
function makeButtons(info) {
  fillSheets(info.sheets);
  const box = $('#make-buttons');
  for (const name of info.artefacts) {
    const b = Object.assign(document.createElement('button'), {type: 'button', textContent: makeLabel(name)});
    b.dataset.make = name;
    b.addEventListener('click', () => make(name));
    box.append(b);
  }
  recipeNote();
  box.dataset.ready = 'true';
}
$('#show-shape').addEventListener('click', () => viewer.setGrid(state.shape));

// --- tabs ---------------------------------------------------------------------------------------

function currentTab() { return $('#tabs .active').dataset.tab; }

$$('#tabs button').forEach((b) => b.addEventListener('click', () => {
  $$('#tabs button').forEach((x) => x.classList.toggle('active', x === b));
  document.body.dataset.tab = b.dataset.tab; // the page's columns follow the tab (studio.css)
  $$('.pane').forEach((p) => p.classList.toggle('active', p.id === `pane-${b.dataset.tab}`));
  if (b.dataset.tab === 'edit') { editor.setGrid(state.shape, {keepHistory: true}); viewer.setLayer(editor.layer); }
  else viewer.setLayer(null);
  if (b.dataset.tab === 'keep') refreshRepo();
}));

// The first shape: the one `voxfab studio SHAPE` was given, else the drawing's preview.
async function start() {
  const {shape} = await get('/api/initial');
  if (!shape) { schedule(true); return; }
  state.opened = true;
  setShape(Grid.unpack(shape.grid), shape.facts, {name: shape.name, label: shape.label.replace(/\.[A-Za-z0-9]+$/, '')});
  $('#shape-name').textContent = shape.label;
  if (shape.pitch) $('#pitch').value = String(shape.pitch);
  say(`Opened ${shape.label}`, true);
}

recipeNote(); netNote();
// The makers table comes with the server's info: the first preview waits for it.
const info = get('/api/info');
info.then((i) => { makers.setTable(i.makers); showMaker(); return start(); }).catch((e) => say(e));
info.then((i) => { makeButtons(i); document.body.dataset.ready = 'true'; }, (e) => say(e));
