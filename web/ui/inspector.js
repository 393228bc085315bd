// The regions of a result: a table (type, key parameter, area, error) and the detail of
// the region in focus, with every parameter and the quadric's equation.
import { element } from './dom.js';
import { css } from './colours.js';
import { format, keyParameters, parameterLines, polynomial, typeName } from './format.js';

// `onFocus(region, pinned)` when the pointer enters a row (pinned false) or a row is
// clicked (pinned true).
export function createInspector(onFocus) {
  const table = element('table', { className: 'vqsa-table' });
  const detail = element('div', { className: 'vqsa-detail' });

  function fill(proxies, colourOf) {
    table.replaceChildren(element('tr', {}, ...['#', 'type', 'parameters', 'area %', 'RMS'].map((t) => element('th', { textContent: t }))));
    if (!proxies) return;
    const total = proxies.reduce((s, p) => s + p.area, 0);
    for (const p of proxies) {
      const swatch = element('span', { className: 'vqsa-swatch' });
      swatch.style.background = css(colourOf(p));
      const row = element('tr', {},
        element('td', {}, swatch, String(p.id)), element('td', { textContent: typeName(p.type) }),
        element('td', { textContent: keyParameters(p) }), element('td', { textContent: ((100 * p.area) / total).toFixed(1) }),
        element('td', { textContent: format(p.metrics?.rms ?? p.rms_error) }));
      row.dataset.region = p.id;
      row.addEventListener('mouseenter', () => onFocus(p.id, false));
      row.addEventListener('click', () => onFocus(p.id, true));
      table.append(row);
    }
  }

  function show(proxy) {
    for (const row of table.querySelectorAll('tr[data-region]'))
      row.classList.toggle('vqsa-selected', Number(row.dataset.region) === proxy?.id);
    detail.replaceChildren();
    if (!proxy) return;
    const lines = [`region ${proxy.id}: ${typeName(proxy.type)}${proxy.special_fit ? ' (refitted)' : ''}`,
      `${proxy.faces} faces, RMS ${format(proxy.metrics?.rms ?? 0)} of the diagonal`,
      // How clear the type choice was: the chosen type's fit to the region's vertices
      // against the best fit of another type.
      ...(proxy.runner_up ? [`type fit RMS ${format(proxy.type_rms)}; runner-up ${typeName(proxy.runner_up.type)}, RMS ${format(proxy.runner_up.rms)}`] : []),
      ...parameterLines(proxy),
      `f = ${polynomial(proxy.coefficients)}`];
    detail.append(...lines.map((l) => element('div', { textContent: l })));
  }

  return { table, detail, fill, show };
}
