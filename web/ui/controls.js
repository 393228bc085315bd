// A settings panel built from field descriptions: the core's option schema (the same
// names, ranges and help as the CLI's flags) or the viewer's own display settings.
//
// A field: {name, label, kind, min, max, choices, labels, help, typicalWhenOn, slider};
// kinds as the schema's: count (a number or 'auto'), integer, number, boolean, choice. A
// number with `typicalWhenOn` is off at 0: it shows as a switch and a field (a slider with
// `slider`).
import { element } from './dom.js';

let nextId = 0;

export function createControls(title, fields, values, onChange) {
  const updaters = [];
  const rows = fields.map((field) => {
    const id = `vqsa-control-${++nextId}`;
    const label = element('label', { htmlFor: id, textContent: field.label ?? field.name });
    const row = element('div', { className: 'vqsa-field', title: field.help ?? '' }, label);
    row.dataset.option = field.name;
    const set = (value) => {
      values[field.name] = value;
      onChange(field.name, value);
    };

    if (field.kind === 'boolean') {
      const box = element('input', { type: 'checkbox', id });
      box.addEventListener('change', () => set(box.checked));
      updaters.push(() => { box.checked = Boolean(values[field.name]); });
      row.append(box);
      return row;
    }
    if (field.kind === 'choice') {
      const select = element('select', { id }, ...field.choices.map((c) =>
        element('option', { value: c, textContent: field.labels?.[c] ?? c })));
      select.addEventListener('change', () => set(select.value));
      updaters.push(() => { select.value = values[field.name]; });
      row.append(select);
      return row;
    }

    // count, integer, number: a field, and for a count ('auto') or a number that 0
    // turns off, a switch beside it.
    const integer = field.kind !== 'number';
    const input = field.slider
      ? element('input', { type: 'range', id, min: field.min, max: field.max, step: (field.max - field.min) / 100 })
      : element('input', { type: 'number', id, min: field.min, max: field.max, step: integer ? 1 : 'any' });
    const switchable = field.kind === 'count' || field.typicalWhenOn !== undefined;
    const off = field.kind === 'count' ? 'auto' : 0;
    const current = values[field.name];
    let remembered = switchable && current === off ? field.typicalWhenOn ?? 20 : current;
    const box = element('input', { type: 'checkbox' });
    const read = () => {
      let v = Number(input.value);
      if (input.value.trim() === '' || !Number.isFinite(v)) v = remembered;
      v = Math.min(Math.max(integer ? Math.round(v) : v, field.min ?? -Infinity), field.max ?? Infinity);
      return v;
    };
    // A slider acts while it moves; a field once its value is entered.
    input.addEventListener(field.slider ? 'input' : 'change', () => {
      remembered = read();
      set(remembered);
      update();
    });
    const update = () => {
      const v = values[field.name];
      const isOff = switchable && v === off;
      if (!isOff) remembered = v;
      // Under 'auto' the field is empty, the count it would take as its placeholder: typing
      // that very number must still be a change that chooses it.
      input.value = isOff && field.kind === 'count' ? '' : String(remembered);
      input.placeholder = String(remembered);
      // A count stays editable under 'auto' (typing one chooses it); a number that is off
      // is not.
      input.disabled = isOff && field.kind !== 'count';
      input.classList.toggle('vqsa-off', isOff);
      box.checked = field.kind === 'count' ? isOff : !isOff;
    };
    updaters.push(update);
    if (switchable) {
      // For a count the switch says 'automatic'; for the others it turns the option on.
      box.addEventListener('change', () => {
        const on = field.kind === 'count' ? !box.checked : box.checked;
        set(on ? remembered : off);
        update();
      });
      box.setAttribute('aria-label', field.kind === 'count' ? `${field.label ?? field.name}: automatic` : `${field.label ?? field.name}: on`);
      row.append(element('span', { className: 'vqsa-input' }, input,
        element('label', { className: 'vqsa-switch' }, box, field.kind === 'count' ? 'auto' : 'on')));
    } else {
      row.append(input);
    }
    return row;
  });

  const panel = element('fieldset', { className: 'vqsa-controls' }, element('legend', { textContent: title }), ...rows);
  const update = () => updaters.forEach((u) => u());
  update();
  return { element: panel, update };
}
