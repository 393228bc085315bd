// The states a run went through — each insertion, split, merge, teleport, and the steps of
// smoothing and refitting — recorded from its progress events, and a slider with play to
// scrub through them after the run.
import { element } from './dom.js';

// Frames keep their labels; past this many bytes every other frame goes (the first and
// the last stay), so a run on a large mesh keeps a coarser history, not all of it.
const MAX_BYTES = 64 * 1024 ** 2;
const PLAY_INTERVAL_MS = 150;

// The frame of a progress event. An operation's event carries its new count with the error
// of the partition it started from (the new one is not flooded yet): on the plot, its point
// is that start, the partition Lloyd last settled on.
export function frameOf(p) {
  const operation = p.stage === 'lloyd' && p.phase !== 'lloyd' && p.settledProxies > 0;
  return { labels: p.labels, proxies: p.proxies, rms: p.rms, stage: p.stage, phase: p.phase, iteration: p.iteration,
           at: operation ? [p.settledProxies, p.settledRms] : [p.proxies, p.rms] };
}

// `show(frame | null)`: draw a recorded frame {labels, proxies, rms, stage, phase, at (its
// point on the plot)}, or the result (null) once the slider is at the end.
export function createTimeline(show) {
  let frames = [], bytes = 0, timer = null;
  const slider = element('input', { type: 'range', min: 0, max: 0, value: 0, ariaLabel: 'timeline of the run' });
  const play = element('button', { textContent: '▶', title: 'Replay the run', ariaLabel: 'replay the run' });
  const root = element('div', { className: 'vqsa-timeline', hidden: true }, play, slider);

  const stop = () => {
    clearInterval(timer);
    timer = null;
    play.textContent = '▶';
  };
  const seek = (index) => {
    slider.value = String(index);
    slider.setAttribute('aria-valuetext', `state ${index + 1} of ${frames.length}`);
    show(index >= frames.length - 1 ? null : frames[index]);
  };
  slider.addEventListener('input', () => {
    stop();
    seek(Number(slider.value));
  });
  play.addEventListener('click', () => {
    if (timer) return stop();
    let index = Number(slider.value) >= frames.length - 1 ? 0 : Number(slider.value);
    play.textContent = '❚❚';
    seek(index);
    timer = setInterval(() => {
      if (++index >= frames.length) return stop();
      seek(index);
    }, PLAY_INTERVAL_MS);
  });

  return {
    element: root,
    get frames() { return frames; },
    clear() {
      stop();
      frames = [];
      bytes = 0;
      root.hidden = true;
    },
    record(frame) {
      frames.push(frame);
      bytes += frame.labels.byteLength;
      if (bytes > MAX_BYTES && frames.length > 2) {
        frames = frames.filter((_, i) => i % 2 === 0 || i === frames.length - 1);
        bytes = frames.reduce((sum, f) => sum + f.labels.byteLength, 0);
      }
    },
    // After the run: the last frame is the result; the slider starts there.
    finish() {
      slider.max = String(frames.length - 1);
      slider.value = slider.max;
      root.hidden = frames.length < 2;
    },
  };
}
