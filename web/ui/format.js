// Numbers and quadrics as the inspector prints them.

// `digits` significant digits whatever the model's size (an r of 0.00123 is not
// "0.001"), exponents only far from 1, no "-0".
export function format(x, digits = 4) {
  if (!Number.isFinite(x)) return String(x);
  const a = Math.abs(x);
  const text = a !== 0 && (a >= 1e5 || a < 1e-3) ? x.toExponential(digits - 1) : x.toPrecision(digits);
  return Number(text) === 0 ? '0' : text;
}

// Components below the last printed digit of the vector's largest are 0: a normal's
// rounding noise (2.6e-7) is not a direction.
export function vector(v, digits = 4) {
  const largest = Math.max(...v.map(Math.abs));
  return `(${v.map((x) => (Math.abs(x) < 0.5 * 10 ** -digits * largest ? '0' : format(x, digits))).join(', ')})`;
}

export const degrees = (radians) => `${((radians * 180) / Math.PI).toFixed(2)}°`;

export const typeName = (type) => type.replaceAll('_', ' ');

// The terms of f = C0 + C1 x + … + C9 z², in the report's order.
const TERMS = ['', 'x', 'y', 'z', 'x²', 'xy', 'xz', 'y²', 'yz', 'z²'];
export function polynomial(c) {
  return c.map((v, i) => [v, i]).filter(([v]) => v !== 0)
    .map(([v, i], k) => `${k === 0 ? (v < 0 ? '−' : '') : v < 0 ? ' − ' : ' + '}${format(Math.abs(v))}${TERMS[i] && ' ' + TERMS[i]}`)
    .join('') || '0';
}

// The one parameter that tells a region's surface at a glance (the table's column).
export function keyParameters(proxy) {
  // A type without its parameter (a general quadric of no real points has none) prints
  // nothing rather than failing.
  const q = proxy.params ?? {};
  switch (proxy.type) {
    case 'plane': return q.normal ? `n ${vector(q.normal, 3)}` : '';
    case 'sphere':
    case 'cylinder': return q.radius !== undefined ? `r ${format(q.radius)}` : '';
    case 'cone': return q.half_angle !== undefined ? degrees(q.half_angle) : '';
    default: return q.semi_axes ? `a ${vector(q.semi_axes, 3)}` : '';
  }
}

// Every parameter of a region, one line each.
export function parameterLines(proxy) {
  return Object.entries(proxy.params ?? {}).map(([k, v]) => `${k.replaceAll('_', ' ')}: ${k === 'half_angle' ? degrees(v)
    : Array.isArray(v[0]) ? v.map((row) => vector(row)).join(' ') : Array.isArray(v) ? vector(v) : format(v)}`);
}

// One edit of the report's list, in words.
export function describeEdit(e) {
  switch (e.op) {
    case 'split': return `split region ${e.region}` + (e.face === undefined ? '' : ` at face ${e.face}`);
    case 'merge': return `merge region ${e.regions[1]} into ${e.regions[0]}`;
    case 'set_type': return e.type === 'none' ? `region ${e.region}: type as fitted` : `region ${e.region}: ${typeName(e.type)} imposed`;
    case 'lock': return `lock region ${e.region}`;
    case 'unlock': return `unlock region ${e.region}`;
    case 'add_seed': return `new region at face ${e.face}`;
    default: return JSON.stringify(e);
  }
}
