// The uniform cubic B-spline basis at t (paper 000, eq. 1), in double: the four weights of a
// segment's control points, written into `out` (a new array when none is given) and returned.
export function bsplineBasis(t, out = [0, 0, 0, 0]) {
  const s = 1 - t, t2 = t * t, t3 = t2 * t;
  out[0] = (s * s * s) / 6;
  out[1] = (3 * t3 - 6 * t2 + 4) / 6;
  out[2] = (-3 * t3 + 3 * t2 + 3 * t + 1) / 6;
  out[3] = t3 / 6;
  return out;
}
