// The camera of lib/render/camera.cpp, in double: auto-framed from an azimuth and elevation
// (--view) or given (--eye/--target/--up); right-handed, depth 0..1, matrices column-major as
// glm's (m[col * 4 + row]), so the same options give limn-render's view.

const FRAME_FILL = 0.85;
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const length = (a) => Math.sqrt(dot(a, a));
const normalize = (a) => mul(a, 1 / length(a));
const radians = (d) => (d * Math.PI) / 180;

function safeUp(forward, up) {
  if (length(cross(forward, up)) > 1e-9 * length(up)) return up;
  return Math.abs(forward[1]) < 0.9 ? [0, 1, 0] : [0, 0, -1];
}
const fromYUp = (d, zUp) => (zUp ? [d[0], -d[2], d[1]] : d);

/** The box, bounding sphere about the box centre, and the points (limn's boundsOf). */
export function boundsOf(points) {
  const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
  for (const p of points) for (let i = 0; i < 3; i++) { min[i] = Math.min(min[i], p[i]); max[i] = Math.max(max[i], p[i]); }
  const c = mul(add(min, max), 0.5);
  let r2 = 0;
  for (const p of points) { const d = sub(p, c); r2 = Math.max(r2, dot(d, d)); }
  return { min, max, sphereRadius: Math.sqrt(r2), hull: points };
}

const center = (b) => mul(add(b.min, b.max), 0.5);
function radius(b) {
  const r = b.sphereRadius > 0 ? b.sphereRadius : length(sub(b.max, b.min)) * 0.5;
  return r > 0 && Number.isFinite(r) ? r : 1;
}

/** frameCamera: spec {azimuthDeg, elevationDeg, fovDeg, zUp, eye?, target?, up?}. */
export function frameCamera(spec, bounds, aspect) {
  const cam = { fovYRad: radians(spec.fovDeg ?? 35) };
  const c = center(bounds), r = radius(bounds);
  const worldUp = fromYUp([0, 1, 0], spec.zUp);
  if (!spec.eye) {
    const az = radians(spec.azimuthDeg ?? -30), el = radians(spec.elevationDeg ?? 20);
    const dir = fromYUp([Math.cos(el) * Math.sin(az), Math.sin(el), Math.cos(el) * Math.cos(az)], spec.zUp);
    cam.up = safeUp(mul(dir, -1), worldUp);
    const right = normalize(cross(mul(dir, -1), cam.up));
    const up = cross(right, mul(dir, -1));
    const tanY = Math.tan(cam.fovYRad * 0.5);
    const k = Math.min(tanY, tanY * aspect) * FRAME_FILL;
    let hiX = -Infinity, loX = Infinity, hiY = -Infinity, loY = Infinity, zMax = -Infinity, zMin = Infinity;
    let points = bounds.hull;
    if (!points || points.length === 0) {
      points = [];
      for (let i = 0; i < 8; i++) points.push([i & 1 ? bounds.max[0] : bounds.min[0], i & 2 ? bounds.max[1] : bounds.min[1], i & 4 ? bounds.max[2] : bounds.min[2]]);
    }
    for (const p of points) {
      const d = sub(p, c);
      const x = dot(d, right), y = dot(d, up), z = dot(d, dir);
      hiX = Math.max(hiX, x + k * z); loX = Math.min(loX, x - k * z);
      hiY = Math.max(hiY, y + k * z); loY = Math.min(loY, y - k * z);
      zMax = Math.max(zMax, z); zMin = Math.min(zMin, z);
    }
    const distance = Math.max((hiX - loX) / (2 * k), (hiY - loY) / (2 * k), zMax + r * 0.05);
    const centre = (axis, t) => {
      for (let it = 0; it < 8; it++) {
        let hi = -Infinity, lo = Infinity, a = [0, 1], b = [0, 1];
        for (const p of points) {
          const d = sub(p, c);
          const y = dot(d, axis), depth = distance - dot(d, dir);
          const projected = (y - t) / depth;
          if (projected > hi) { hi = projected; a = [y, depth]; }
          if (projected < lo) { lo = projected; b = [y, depth]; }
        }
        const next = (a[0] * b[1] + b[0] * a[1]) / (a[1] + b[1]);
        if (next === t || !(a[1] > 0 && b[1] > 0)) break;
        t = next;
      }
      return t;
    };
    const s = centre(right, (hiX + loX) * 0.5), t = centre(up, (hiY + loY) * 0.5);
    cam.target = add(add(c, mul(right, s)), mul(up, t));
    cam.eye = add(cam.target, mul(dir, distance));
    cam.nearPlane = Math.max(Math.min(distance - zMax, distance - r) * 0.98, distance * 1e-4);
    cam.farPlane = Math.max(distance - zMin, distance + r) * 1.02;
    return cam;
  }
  cam.eye = spec.eye;
  cam.target = spec.target ?? c;
  if (length(sub(cam.target, cam.eye)) === 0) cam.target = add(cam.eye, [0, 0, -1]);
  cam.up = safeUp(sub(cam.target, cam.eye), spec.up ?? worldUp);
  const toCenter = length(sub(c, cam.eye));
  cam.farPlane = toCenter + r * 1.02;
  cam.nearPlane = Math.max(toCenter - r * 1.02, cam.farPlane * 1e-4);
  return cam;
}

/** glm::lookAtRH(eye, target, safeUp(target - eye, up)), column-major. */
export function viewMatrix(cam) {
  const f = normalize(sub(cam.target, cam.eye));
  const s = normalize(cross(f, safeUp(sub(cam.target, cam.eye), cam.up)));
  const u = cross(s, f);
  return [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, -dot(s, cam.eye), -dot(u, cam.eye), dot(f, cam.eye), 1];
}

/** glm::perspectiveRH_ZO, column-major. */
export function projectionMatrix(cam, aspect) {
  const t = Math.tan(cam.fovYRad / 2), n = cam.nearPlane, f = cam.farPlane;
  const m = new Array(16).fill(0);
  m[0] = 1 / (aspect * t);
  m[5] = 1 / t;
  m[10] = f / (n - f);
  m[11] = -1;
  m[14] = -(f * n) / (f - n);
  return m;
}

export function multiply(a, b) {
  const m = new Array(16).fill(0);
  for (let c = 0; c < 4; c++) for (let r = 0; r < 4; r++) for (let k = 0; k < 4; k++) m[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
  return m;
}

export { normalize, cross, sub, dot, mul, add };
