// The core's palette (the GLB's colours too) and the error heat ramp. Colours are linear
// RGB arrays, as Three.js's vertex colours take them.
import { palette } from '../vqsa-schema.js';

export const NEUTRAL = [0.72, 0.74, 0.78];

export const regionColour = (region) => palette.regions[region % palette.regions.length];
export const typeColour = (type) => palette.types[type] ?? NEUTRAL;

// Blue → cyan → yellow → red, t in [0, 1].
const HEAT = [[0.15, 0.25, 0.8], [0.1, 0.75, 0.85], [0.95, 0.85, 0.2], [0.85, 0.1, 0.1]];
export function heat(t) {
  const x = Math.min(Math.max(t, 0), 1) * (HEAT.length - 1), i = Math.min(Math.floor(x), HEAT.length - 2), f = x - i;
  return HEAT[i].map((v, k) => v + f * (HEAT[i + 1][k] - v));
}

const srgb = (c) => (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055);
export const css = (rgb) => `rgb(${rgb.map((c) => Math.round(255 * srgb(Math.min(Math.max(c, 0), 1)))).join(',')})`;
