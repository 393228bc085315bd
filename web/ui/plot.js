// The RMS error against the proxy count, on a log scale: the paper's progressive
// insertion as a curve (the least error with each count or fewer). `growth`: [count, rms]
// of the partitions the run settled on; `result`: the run's [count, rms], a ring; `marker`:
// a [count, rms] to mark (the timeline's state, an edited result), or null.
export function drawPlot(canvas, growth, result = null, marker = null) {
  const g = canvas.getContext('2d'), w = canvas.width, h = canvas.height, pad = 26;
  // The theme's colours (viewer.css), light or dark.
  const style = getComputedStyle(canvas), colour = (name, fallback) => style.getPropertyValue(name).trim() || fallback;
  const ink = colour('--vqsa-plot-ink', '#556'), frame = colour('--vqsa-plot-frame', '#ccd');
  g.clearRect(0, 0, w, h);
  g.fillStyle = colour('--vqsa-plot-background', '#fff');
  g.fillRect(0, 0, w, h);
  g.strokeStyle = frame;
  g.strokeRect(pad, 6, w - pad - 6, h - pad);
  // The least error reached with each count or fewer: a count is passed through more than
  // once (splits, merges, teleports), and a run that merges back (the surfaces found, the
  // extra proxies merged away) reaches at a lower count an error its growth reached only
  // later: drawn as it was reached, the curve would dip there.
  const least = new Map();
  for (const [n, rms] of growth) if (rms > 0 && !(least.get(n) <= rms)) least.set(n, rms);
  const points = [...least].sort((a, b) => a[0] - b[0]);
  for (let i = 1; i < points.length; ++i) points[i][1] = Math.min(points[i][1], points[i - 1][1]);
  if (points.length < 2) return;
  // The axes hold the result and the marker too (an edited result may have more proxies,
  // or another error, than the run passed through).
  const dots = [result, marker].filter((d) => d && d[1] > 0);
  const shown = [...points, ...dots];
  const maxN = Math.max(...shown.map(([n]) => n)), logs = shown.map(([, r]) => Math.log10(r));
  const lo = Math.floor(Math.min(...logs)), hi = Math.ceil(Math.max(...logs)) + (Math.min(...logs) === Math.max(...logs) ? 1 : 0);
  const x = (n) => pad + ((n - 1) / Math.max(1, maxN - 1)) * (w - pad - 8);
  const y = (r) => 6 + ((hi - Math.log10(r)) / (hi - lo)) * (h - pad - 2);
  g.fillStyle = ink;
  g.font = '10px sans-serif';
  // A label every few decades where one each would overlap (an exact part's run spans 15).
  const step = Math.max(1, Math.ceil(((hi - lo) * 12) / (h - pad - 2)));
  for (let e = hi; e >= lo; e -= step) g.fillText(`1e${e}`, 0, y(10 ** e) + 3);
  g.fillText('proxies', w / 2 - 15, h - 4);
  g.fillText('1', pad - 2, h - 14);
  // Ends at the frame's right edge: a run grown to thousands of proxies has a four-digit count.
  g.textAlign = 'right';
  g.fillText(String(maxN), w - 6, h - 14);
  g.textAlign = 'left';
  g.strokeStyle = colour('--vqsa-accent', '#2864c8');
  g.lineWidth = 1.5;
  g.beginPath();
  points.forEach(([n, r], i) => (i ? g.lineTo(x(n), y(r)) : g.moveTo(x(n), y(r))));
  g.stroke();
  if (result && result[1] > 0) {
    g.beginPath();
    g.arc(x(result[0]), y(result[1]), 3.5, 0, 2 * Math.PI);
    g.stroke();
  }
  if (marker && marker[1] > 0) {
    g.fillStyle = '#d0402a';
    g.beginPath();
    g.arc(x(marker[0]), y(marker[1]), 3.5, 0, 2 * Math.PI);
    g.fill();
  }
}
