// <vqsa-viewer src="model.obj" proxies="20" rings="2"></vqsa-viewer>
//
// A custom element around createViewer(). Its attributes are its API: `src` (a mesh URL)
// or `example` (a built-in example's name), and every option of the core's schema under
// the CLI's name (proxies="auto", tolerance="0.002", max-iterations, seed, init,
// crease-angle, smooth="false", rings, lambda, refit, project, measure). Each is also a
// property under its camelCase name (element.maxIterations = 50 sets the attribute).
// The element loads its mesh when attached and runs again when an option changes (changes
// made together run once). It fires the viewer's events: state, loaded, progress, result,
// edit, and error with detail {type: 'load' | 'run' | 'edit' | 'engine', message}; `.viewer`
// is the viewer's module API. Edits of the result are methods, each a promise of the new
// report (docs/EDITS.md): split(id, face?), merge(a, b), setType(id, type), lock(id),
// unlock(id), addSeed(face), undo(), redo(). Its parts live in its shadow root, styles
// included.
import { createViewer } from './viewer.js';
import { options as schema } from './vqsa-schema.js';

const EVENTS = ['state', 'loaded', 'progress', 'result', 'edit', 'error'];
const EDITS = ['split', 'merge', 'setType', 'lock', 'unlock', 'addSeed', 'undo', 'redo'];

// An attribute's text as the option's value (the core checks the ranges). A boolean is
// true when present without a value (<vqsa-viewer measure>); the words the core reads as
// booleans (the schema's `words`) become booleans (the settings panel shows them), any
// other text goes to the core as it is, which rejects it with an error event naming the option.
function parse(option, text) {
  if (option.kind === 'boolean') {
    const word = text.trim().toLowerCase();
    return word === '' ? true : Object.hasOwn(option.words, word) ? option.words[word] : text;
  }
  if (option.kind === 'choice' || (option.kind === 'count' && text.trim() === 'auto')) return text.trim();
  return text.trim() === '' ? NaN : Number(text);
}

class VqsaViewerElement extends HTMLElement {
  static observedAttributes = ['src', 'example', ...schema.map((o) => o.name)];
  #viewer = null;
  #loading = null;
  #runQueued = false;

  get viewer() {
    return this.#viewer;
  }

  // The options set by attributes, camelCase.
  #options() {
    const out = {};
    for (const o of schema) if (this.hasAttribute(o.name)) out[o.js] = parse(o, this.getAttribute(o.name));
    return out;
  }

  connectedCallback() {
    if (this.#viewer) return;
    this.#viewer = createViewer(this, this.#options());
    for (const type of EVENTS)
      this.#viewer.addEventListener(type, (e) => this.dispatchEvent(new CustomEvent(type, { detail: e.detail })));
    this.#load();
  }

  disconnectedCallback() {
    this.#viewer?.destroy();
    this.#viewer = null;
  }

  attributeChangedCallback(name, previous, value) {
    if (!this.#viewer || previous === value) return;
    if (name === 'src' || name === 'example') this.#load();
    else this.#queueRun();
  }

  // Loads src (or example), then runs with the attributes' options; nothing runs after a
  // failed load.
  #load() {
    const src = this.getAttribute('src'), example = this.getAttribute('example') ?? 'turned_part';
    const loading = src ? this.#viewer.load(src) : this.#viewer.loadExample(example);
    this.#loading = loading;
    loading.then((info) => {
      if (this.#loading === loading) this.#loading = null;
      if (info && this.#viewer) this.#viewer.run(this.#options());
    });
  }

  // Several attributes set in one task run once; during a load, the run after it takes them.
  #queueRun() {
    if (this.#runQueued) return;
    this.#runQueued = true;
    queueMicrotask(() => {
      this.#runQueued = false;
      if (this.#viewer && !this.#loading && this.#viewer.state !== 'loading') this.#viewer.run(this.#options());
    });
  }
}

// Reflected properties: element.proxies, element.maxIterations, … read and write the attributes.
for (const o of schema)
  Object.defineProperty(VqsaViewerElement.prototype, o.js, {
    get() {
      return this.hasAttribute(o.name) ? parse(o, this.getAttribute(o.name)) : o.default;
    },
    set(value) {
      this.setAttribute(o.name, String(value));
    },
  });
for (const name of EDITS)
  Object.defineProperty(VqsaViewerElement.prototype, name, {
    value(...args) {
      if (!this.viewer) return Promise.reject(new Error('the element is not in a document'));
      return this.viewer[name](...args);
    },
  });
for (const name of ['src', 'example'])
  Object.defineProperty(VqsaViewerElement.prototype, name, {
    get() {
      return this.getAttribute(name);
    },
    set(value) {
      this.setAttribute(name, value);
    },
  });

if (!customElements.get('vqsa-viewer')) customElements.define('vqsa-viewer', VqsaViewerElement);
