// Orbit, zoom and pan as edits of limn-render's camera options. A framed view (--view AZ,EL: the
// object auto-framed from that direction) stays framed while it only turns; zooming or panning
// makes the camera explicit (--eye/--target), which turns around its target; 'frame' goes back to
// a framed view from the current direction. Pure functions on the viewer state (state.mjs).
import { roundAngle, roundPoint } from './state.mjs';

const D = Math.PI / 180;
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const len = (a) => Math.hypot(a[0], a[1], a[2]);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => mul(a, 1 / len(a));

// limn-render's --up-axis z sees the asset turned Y-up by (x, y, z) -> (x, z, -y).
const fromYUp = (d, zUp) => (zUp ? [d[0], -d[2], d[1]] : d);
const toYUp = (w, zUp) => (zUp ? [w[0], w[2], -w[1]] : w);

export const wrapAzimuth = (a) => ((((a + 180) % 360) + 360) % 360) - 180;
const clampElevation = (e) => Math.min(89.9, Math.max(-89.9, e));

/** Azimuth and elevation (degrees) of the direction from target to eye. */
export function anglesOf(direction, zUp) {
  const d = toYUp(norm(direction), zUp);
  return [Math.atan2(d[0], d[2]) / D, Math.asin(Math.max(-1, Math.min(1, d[1]))) / D];
}

export function directionOf([az, el], zUp) {
  return fromYUp([Math.cos(el * D) * Math.sin(az * D), Math.sin(el * D), Math.cos(el * D) * Math.cos(az * D)], zUp);
}

const explicit = (state, eye, target) => ({ ...state, eye: roundPoint(eye), target: roundPoint(target), up: null });

/** Turns the view by dAz, dEl degrees. `camera`: the drawn camera ({eye, target}). */
export function orbit(state, dAz, dEl, camera) {
  const zUp = state.upAxis === 'z';
  if (!state.eye) return { ...state, view: [roundAngle(wrapAzimuth(state.view[0] + dAz)), roundAngle(clampElevation(state.view[1] + dEl))] };
  const target = state.target ?? camera.target;
  const [az, el] = anglesOf(sub(state.eye, target), zUp);
  const distance = len(sub(state.eye, target));
  const eye = add(target, mul(directionOf([az + dAz, clampElevation(el + dEl)], zUp), distance));
  return explicit(state, eye, target);
}

/** Moves the eye towards the target by `factor` (< 1 zooms in); the camera becomes explicit. */
export function zoom(state, factor, camera) {
  const target = state.target ?? camera.target, eye = state.eye ?? camera.eye;
  const offset = sub(eye, target);
  const distance = Math.max(len(offset) * factor, 1e-6);
  return explicit(state, add(target, mul(norm(offset), distance)), target);
}

/** Moves eye and target by (dx, dy) pixels of an image `height` pixels high. */
export function pan(state, dx, dy, camera, height) {
  const target = state.target ?? camera.target, eye = state.eye ?? camera.eye;
  const forward = norm(sub(target, eye));
  const right = norm(cross(forward, camera.up));
  const up = cross(right, forward);
  const perPixel = (2 * len(sub(eye, target)) * Math.tan((state.fov * D) / 2)) / height;
  const move = add(mul(right, -dx * perPixel), mul(up, dy * perPixel));
  return explicit(state, add(eye, move), add(target, move));
}

/** Back to a framed view (--view) from the current direction. */
export function frame(state, camera) {
  const [az, el] = anglesOf(sub(camera.eye, camera.target), state.upAxis === 'z');
  return { ...state, eye: null, target: null, up: null, view: [roundAngle(az), roundAngle(clampElevation(el))] };
}

/** The renderer's view spec (camera.mjs frameCamera) of a state. */
export function viewSpec(state) {
  const v = { fovDeg: state.fov, zUp: state.upAxis === 'z' };
  if (state.eye) return { ...v, eye: state.eye, target: state.target ?? undefined, up: state.up ?? undefined };
  return { ...v, azimuthDeg: state.view[0], elevationDeg: state.view[1] };
}
