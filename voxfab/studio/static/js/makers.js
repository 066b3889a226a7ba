// The makers table as the page offers it (the server's /api/info): the maker select lists every
// maker of the table, and each maker's form keys get a field generated from their row.

// The page's own words for the makers it draws for; any other maker is offered by its table name.
const MAKER_LABELS = {revolution: 'Surface of revolution', tube: 'Tube', focal: 'Egg (foci)', implicit: 'Expression (implicit)'};

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) if (v !== null && v !== undefined) e.setAttribute(k, String(v));
  e.append(...children);
  return e;
}

// The tooltip of a key: its help, type and range, as the row says them.
function tooltip(p) {
  const range = p.low !== null && p.high !== null ? `, ${p.low} to ${p.high}` : p.low !== null ? `, at least ${p.low}`
    : p.high !== null ? `, at most ${p.high}` : '';
  return `${p.help} (${p.name}: ${p.type}${range}${p.required ? ', required' : ''})`;
}

// One field for key `p`: a number input with the row's range, a select of its words, a checkbox, or a
// text of numbers. The default is filled in; a key without one starts empty (the maker's own choice).
function field(p) {
  const common = {'data-param': p.name, 'data-kind': p.kind};
  if (p.kind === 'integer' || p.kind === 'number') {
    return el('input', {...common, type: 'number', min: p.low, max: p.high, step: p.kind === 'integer' ? 1 : 'any',
      value: p.default === null ? null : p.default, placeholder: p.default === null ? 'auto' : null});
  }
  if (p.kind === 'word' || (p.kind === 'flag' && p.default === null)) {
    // a flag without a default has three states: the maker decides, yes, no
    const words = p.kind === 'word' ? p.choices.map((c) => [c, c]) : [['true', 'yes'], ['false', 'no']];
    const options = [...(p.default === null ? [['', 'auto']] : []), ...words]
      .map(([value, text]) => el('option', {value}, text));
    const select = el('select', common, ...options);
    select.value = p.default === null ? '' : String(p.default);
    return select;
  }
  if (p.kind === 'flag') {
    const box = el('input', {...common, type: 'checkbox'});
    box.checked = Boolean(p.default);
    return box;
  }
  return el('input', {...common, type: 'text', size: 14, placeholder: 'numbers, e.g. 0, 0, 0',
    value: Array.isArray(p.default) ? p.default.join(', ') : null});
}

// A field's value as the maker takes it, or undefined when it is empty (the maker's default).
function valueOf(input) {
  const kind = input.dataset.kind, raw = input.type === 'checkbox' ? input.checked : input.value.trim();
  if (raw === '') return undefined;
  if (kind === 'integer' || kind === 'number') return Number(raw);
  if (kind === 'flag') return typeof raw === 'boolean' ? raw : raw === 'true';
  // a token that is no number goes as it is typed: the server names it
  if (kind === 'numbers') return raw.split(/[\s,;]+/).filter((t) => t).map((t) => (Number.isFinite(Number(t)) ? Number(t) : t));
  return raw;
}

export class MakerForms {
  // `select`: the maker select; `box`: where a maker's generated fields go; `own(maker)`: the keys the
  // page has controls of its own for (the drawing's, k and mode); `onChange`: a field changed.
  constructor(select, box, {own, onChange}) {
    this.select = select; this.box = box; this.own = own; this.onChange = onChange; this.rows = new Map();
    box.addEventListener('change', () => this.onChange());
  }

  // Fill the select with every maker of the table, in its order, and show the first one's form.
  setTable(makers) {
    this.rows = new Map(makers.map((m) => [m.name, m]));
    this.select.replaceChildren(...makers.map((m) =>
      el('option', {value: m.name, title: m.help}, this.label(m.name))));
    this.show();
  }

  // The words the Maker menu shows for a maker ("focal": its option's).
  label(maker) { return MAKER_LABELS[maker] || maker; }

  // The table's row of the chosen maker (none before the table is read).
  row(maker = this.select.value) { return this.rows.get(maker) || {name: maker, params: []}; }

  // Whether the chosen maker takes key `name`, and whether the page's drawing gives it.
  takes(name) { return this.row().params.some((p) => p.name === name); }
  drawn(name) { return this.row().params.some((p) => p.name === name && p.input === 'drawn'); }

  // The fields of the chosen maker's form keys that the page has no control of its own for.
  show() {
    const row = this.row(), own = this.own(row.name);
    const fields = row.params.filter((p) => p.input === 'form' && !own.includes(p.name)).map((p) =>
      el('label', {title: tooltip(p), 'data-testid': `param-${p.name}`}, `${p.label || p.name} `, field(p)));
    this.box.replaceChildren(...fields);
    this.box.dataset.maker = row.name;
  }

  // The values of the generated fields that differ from their row's default: the recipe names only those.
  values() {
    const out = {};
    for (const input of this.box.querySelectorAll('[data-param]')) {
      const p = this.row().params.find((q) => q.name === input.dataset.param);
      const value = valueOf(input);
      if (value !== undefined && JSON.stringify(value) !== JSON.stringify(p.default)) out[p.name] = value;
    }
    return out;
  }
}
