// element('button', { textContent: 'Run', dataset: { testid: 'run' } }, ...children)
export function element(tag, { dataset = {}, ...properties } = {}, ...children) {
  const e = Object.assign(document.createElement(tag), properties);
  Object.assign(e.dataset, dataset);
  e.append(...children);
  return e;
}
