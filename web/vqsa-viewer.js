// <vqsa-viewer src="model.obj" proxies="20" rings="1" lambda="1"></vqsa-viewer>  (proxies="auto": automatic count)
// A custom element around createViewer(): it approximates `src` (or `example`) when
// attached, re-runs when `proxies` changes, and exposes the viewer as `.viewer`.
import { createViewer } from './viewer.js';

// A proxy count attribute: a number, or 'auto' for the automatic count.
const count = (value) => (value === 'auto' ? 'auto' : Number(value));

class VqsaViewerElement extends HTMLElement {
  static observedAttributes = ['src', 'proxies'];
  #viewer = null;

  get viewer() {
    return this.#viewer;
  }

  connectedCallback() {
    if (this.#viewer) return;
    const number = (name) => (this.hasAttribute(name) ? Number(this.getAttribute(name)) : undefined);
    this.#viewer = createViewer(this, {
      src: this.getAttribute('src') ?? undefined,
      example: this.getAttribute('src') ? undefined : this.getAttribute('example') ?? 'turned_part',
      proxies: this.hasAttribute('proxies') ? count(this.getAttribute('proxies')) : undefined,
      rings: number('rings'), lambda: number('lambda'), seed: number('seed'),
    });
  }

  disconnectedCallback() {
    this.#viewer?.destroy();
    this.#viewer = null;
  }

  attributeChangedCallback(name, previous, value) {
    if (!this.#viewer || previous === value) return;
    if (name === 'src' && value) this.#viewer.load(value).then(() => this.#viewer.run());
    if (name === 'proxies' && value) this.#viewer.run({ proxies: count(value) });
  }
}

if (!customElements.get('vqsa-viewer')) customElements.define('vqsa-viewer', VqsaViewerElement);
