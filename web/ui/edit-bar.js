// The edit controls for the region in focus: split (at its worst face, or at a face you
// pick), merge with a neighbour you pick, impose a type, lock, add a seed at a face you
// pick; undo and redo. What they do is the caller's (the viewer's `act`); this module only
// says which edit was asked for and which face pick is pending.
//
// Keyboard (in the view): S splits, Shift+S splits at a picked face, M merges with the
// region under the pointer (or the next one clicked), A adds a seed at the next face
// clicked, L locks or unlocks, Ctrl+Z undoes, Ctrl+Shift+Z or Ctrl+Y redoes, Escape drops a
// pending pick. Shift-click on another region merges it into the one in focus.
import { element } from './dom.js';

export const IMPOSED_TYPES = { none: 'as fitted', plane: 'plane', sphere: 'sphere', cylinder: 'cylinder', cone: 'cone',
  quadric: 'general quadric' };

const PICK_PROMPTS = {
  split: 'click a face of the region: it seeds the new region (Escape: cancel)',
  merge: 'click the region to merge into this one (Escape: cancel)',
  seed: 'click a face: a new region grows from it (Escape: cancel)',
};

// `act(kind, ...)`: 'split' (region, and the picked face or nothing), 'merge' (region,
// other), 'type' (region, type), 'lock' (region, locked), 'seed' (face), 'pick' (mode:
// split | merge | seed, or null: the view's cursor), 'undo', 'redo'. Faces are the
// view's triangle indices.
export function createEditBar(act) {
  const button = (textContent, title, onClick, testid) => {
    const b = element('button', { textContent, title, dataset: { testid } });
    b.addEventListener('click', onClick);
    return b;
  };
  let region = null;  // the proxy in focus (pinned), or null
  let pending = null;
  const prompt = element('div', { className: 'vqsa-edit-prompt', hidden: true });
  const split = button('Split', 'Split the region at its worst face (S)', () => act('split', region.id), 'edit-split');
  const splitAt = button('Split at…', 'Split the region at a face you click (Shift+S)', () => pick('split'), 'edit-split-at');
  const merge = button('Merge with…', 'Merge a neighbour you click into this region (M, or Shift-click it)', () => pick('merge'), 'edit-merge');
  const lock = button('Lock', 'Keep this region as it is through later edits (L)', () => act('lock', region.id, !region.locked), 'edit-lock');
  const type = element('select', { title: 'Impose a type on the region', ariaLabel: 'Impose a type', dataset: { testid: 'edit-type' } },
    ...Object.entries(IMPOSED_TYPES).map(([value, label]) => element('option', { value, textContent: `type: ${label}` })));
  type.addEventListener('change', () => act('type', region.id, type.value));
  const seed = button('Add seed…', 'Grow a new region from a face you click (A)', () => pick('seed'), 'edit-seed');
  const undo = button('Undo', 'Undo the last edit (Ctrl+Z)', () => act('undo'), 'edit-undo');
  const redo = button('Redo', 'Redo (Ctrl+Shift+Z)', () => act('redo'), 'edit-redo');
  const regionTools = [split, splitAt, merge, type, lock];
  const host = element('div', { className: 'vqsa-edit' },
    element('div', { className: 'vqsa-edit-bar' }, split, splitAt, merge, lock),
    element('div', { className: 'vqsa-edit-bar' }, type, seed, undo, redo), prompt);

  function pick(mode) {
    pending = mode;
    prompt.hidden = !mode;
    prompt.textContent = mode ? PICK_PROMPTS[mode] : '';
    act('pick', mode);
  }

  // `proxy`: the region in focus (null: none); `history`: {canUndo, canRedo}; `enabled`:
  // a result is shown and nothing runs.
  function update(proxy, history, enabled) {
    region = proxy;
    for (const control of regionTools) control.disabled = !enabled || !proxy;
    for (const control of [split, splitAt, merge, type]) control.disabled ||= Boolean(proxy?.locked);
    seed.disabled = !enabled;
    undo.disabled = !enabled || !history?.canUndo;
    redo.disabled = !enabled || !history?.canRedo;
    lock.textContent = proxy?.locked ? 'Unlock' : 'Lock';
    type.value = proxy?.imposed_type ?? 'none';
    if (!enabled && pending) pick(null);
  }

  // A key in the view; true when it was an edit's.
  function key(event, hovered) {
    const k = event.key.toLowerCase(), command = event.ctrlKey || event.metaKey;
    if (command) {
      const wanted = k === 'z' && !event.shiftKey ? undo : k === 'y' || k === 'z' ? redo : null;
      if (!wanted || wanted.disabled) return false;
      act(wanted === undo ? 'undo' : 'redo');
      return true;
    }
    if (event.altKey) return false;
    if (k === 'escape' && pending) return pick(null), true;
    if (k === 'a' && !seed.disabled) return pick('seed'), true;
    if (!region) return false;
    if (k === 's' && !split.disabled) return event.shiftKey ? pick('split') : act('split', region.id), true;
    if (k === 'l' && !lock.disabled) return act('lock', region.id, !region.locked), true;
    if (k === 'm' && !merge.disabled) {
      if (hovered >= 0 && hovered !== region.id) act('merge', region.id, hovered);
      else pick('merge');
      return true;
    }
    return false;
  }

  // The face (and its region) a click picked while a pick is pending: true when it was
  // taken for one.
  function picked(face, faceRegion) {
    if (!pending || face < 0) return false;
    const mode = pending;
    pick(null);
    if (mode === 'seed') act('seed', face);
    else if (mode === 'split') act('split', region.id, face);
    else if (faceRegion !== region.id) act('merge', region.id, faceRegion);
    return true;
  }

  return { element: host, update, key, picked, get pending() { return pending; } };
}
