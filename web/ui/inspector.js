// The regions of a result: a table (visibility, type, key parameter, area, error) and the
// detail of the region in focus, with every parameter, the quadric's equation and its JSON
// to copy.
//
// Keyboard: rows are focusable; ↑/↓ move, Enter or Space pins the region, H hides or shows
// it, I isolates it (again: shows all), F frames it, Escape unpins; other keys go on to the
// viewer (the edit keys). Shift-click merges a row's region into the pinned one.
import { element } from './dom.js';
import { css } from './colours.js';
import { format, keyParameters, parameterLines, polynomial, typeName } from './format.js';

// The type, and what edits hold of it.
const typeLabel = (p) => typeName(p.type) + (p.imposed_type ? ' (imposed)' : '') + (p.locked ? ' · locked' : '');

// A region of a few faces may get no measurement sample: its RMS is unknown, not 0.
const unsampled = (p) => p.metrics && p.metrics.rms === null;
const noSample = 'no measurement sample fell in this region';

// Callbacks: focus(region, pinned) when a row is entered (pinned false), clicked or keyed
// (pinned true; region -1 unpins); visibility(hiddenSet) when regions are hidden or shown;
// frame(region); merge(region) when a row is shift-clicked (into the pinned one).
export function createInspector({ focus, visibility, frame, merge }) {
  const table = element('table', { className: 'vqsa-table' });
  const detail = element('div', { className: 'vqsa-detail' });
  let proxies = null;
  let hidden = new Set();
  const rowOf = (region) => table.querySelector(`tr[data-region="${region}"]`);

  function setHidden(next) {
    hidden = next;
    for (const row of table.querySelectorAll('tr[data-region]')) {
      const region = Number(row.dataset.region), shown = !hidden.has(region);
      row.querySelector('input').checked = shown;
      row.classList.toggle('vqsa-hidden', !shown);
    }
    visibility(hidden);
  }
  const toggle = (region) => {
    const next = new Set(hidden);
    if (!next.delete(region)) next.add(region);
    setHidden(next);
  };
  // Isolating the only visible region shows everything again.
  const isolate = (region) => {
    const alone = proxies.length - hidden.size === 1 && !hidden.has(region);
    setHidden(alone ? new Set() : new Set(proxies.map((p) => p.id).filter((id) => id !== region)));
  };

  function onKey(event, region) {
    const rows = [...table.querySelectorAll('tr[data-region]')], index = rows.indexOf(event.currentTarget);
    const move = { ArrowDown: 1, ArrowUp: -1 }[event.key];
    if (move) rows[Math.min(Math.max(index + move, 0), rows.length - 1)].focus();
    else if (event.key === 'Enter' || event.key === ' ') focus(region, true);
    else if (event.key === 'Escape') focus(-1, true);
    else if (event.key.toLowerCase() === 'h') toggle(region);
    else if (event.key.toLowerCase() === 'i') isolate(region);
    else if (event.key.toLowerCase() === 'f') frame(region);
    else return;
    event.preventDefault();
  }

  function fill(list, colourOf) {
    proxies = list;
    hidden = new Set();
    table.replaceChildren(element('tr', {}, ...['', '#', 'type', 'parameters', 'area %', 'RMS'].map((t) => element('th', { textContent: t }))));
    if (!list) return;
    const total = list.reduce((s, p) => s + p.area, 0);
    for (const p of list) {
      const swatch = element('span', { className: 'vqsa-swatch' });
      swatch.style.background = css(colourOf(p));
      const shown = element('input', { type: 'checkbox', checked: true, title: 'show (H); I isolates', tabIndex: -1,
        ariaLabel: `show region ${p.id}` });
      shown.addEventListener('click', (e) => e.stopPropagation());
      shown.addEventListener('change', () => toggle(p.id));
      const row = element('tr', { tabIndex: 0, dataset: { region: p.id } },
        element('td', {}, shown), element('td', {}, swatch, String(p.id)), element('td', { textContent: typeLabel(p) }),
        element('td', { textContent: keyParameters(p) }), element('td', { textContent: ((100 * p.area) / total).toFixed(1) }),
        element('td', unsampled(p) ? { textContent: '–', title: noSample } : { textContent: format(p.metrics?.rms ?? p.rms_error) }));
      row.addEventListener('mouseenter', () => focus(p.id, false));
      row.addEventListener('click', (e) => (e.shiftKey ? merge(p.id) : focus(p.id, true)));
      row.addEventListener('dblclick', () => isolate(p.id));
      row.addEventListener('keydown', (e) => onKey(e, p.id));
      table.append(row);
    }
  }

  // Shows `proxy` (or nothing) in the detail, marks its row and scrolls it into view.
  function show(proxy) {
    for (const row of table.querySelectorAll('tr[data-region]'))
      row.classList.toggle('vqsa-selected', Number(row.dataset.region) === proxy?.id);
    if (proxy) rowOf(proxy.id)?.scrollIntoView({ block: 'nearest' });
    detail.replaceChildren();
    if (!proxy) return;
    const lines = [`region ${proxy.id}: ${typeLabel(proxy)}${proxy.special_fit ? ' (refitted)' : ''}`,
      `${proxy.faces} faces, ` + (unsampled(proxy) ? `RMS unmeasured (${noSample})`
        : proxy.metrics ? `RMS ${format(proxy.metrics.rms)} of the diagonal` : `fit RMS ${format(proxy.rms_error)}`),
      // How clear the type choice was: the chosen type's fit to the region's vertices
      // against the best fit of another type.
      ...(proxy.runner_up ? [`type fit RMS ${format(proxy.type_rms)}; runner-up ${typeName(proxy.runner_up.type)}, RMS ${format(proxy.runner_up.rms)}`] : []),
      ...parameterLines(proxy),
      `f = ${polynomial(proxy.coefficients)}`];
    const copy = element('button', { textContent: 'Copy JSON', title: 'Copy the region as the report gives it' });
    copy.addEventListener('click', async () => {
      await navigator.clipboard?.writeText(JSON.stringify(proxy, null, 2));
      copy.textContent = 'Copied';
      setTimeout(() => { copy.textContent = 'Copy JSON'; }, 1200);
    });
    const actions = element('div', { className: 'vqsa-actions' }, copy);
    for (const [label, action] of [['Isolate', isolate], ['Frame', frame]]) {
      const button = element('button', { textContent: label });
      button.addEventListener('click', () => action(proxy.id));
      actions.append(button);
    }
    detail.append(...lines.map((l) => element('div', { textContent: l })), actions);
  }

  return { table, detail, fill, show, focusRow: (region) => rowOf(region)?.focus(), get hidden() { return hidden; } };
}
