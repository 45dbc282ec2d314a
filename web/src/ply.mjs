// The drawn surface as PLY, byte for byte as limn-render's --mesh-out (lib/export/ply.cpp): one
// vertex per drawn corner with `float x y z nx ny nz`, `int ptex`, `float u v`, then `float s t`
// (the texture UV) when the mesh has texture coordinates, then `uchar approximate` when some
// vertex is not on the limit surface, and faces as `list uchar int vertex_indices`. Binary
// little-endian, or ASCII with each float as the shortest text that reads back to the same float
// (C++'s std::to_chars).

/** std::to_chars(float): the fewest significant digits that read back to `x` as a float, in
 * fixed or scientific notation, whichever is shorter (fixed on a tie). */
export function shortestFloat(x) {
  if (x === 0) return Object.is(x, -0) ? '-0' : '0';
  if (!Number.isFinite(x)) return Number.isNaN(x) ? 'nan' : x > 0 ? 'inf' : '-inf';
  const ax = Math.abs(x);
  let digits = '', exponent = 0;
  for (let p = 1; p <= 9; p++) {
    // The nearest p-digit decimal (toExponential rounds a tie up, to_chars to even: redone below).
    const e = ax.toExponential(p - 1);
    if (Math.fround(Number(e)) === ax) {
      const [mantissa, exp] = e.split('e');
      digits = mantissa.replace('.', '');
      exponent = Number(exp);
      // A float is a finite binary fraction: 100 digits hold it exactly (within limn's range).
      const [exactMantissa, exactExp] = ax.toExponential(100).split('e');
      const exact = exactMantissa.replace('.', ''), down = exact.slice(0, p);
      if (/^50*$/.test(exact.slice(p)) && Number(down[p - 1]) % 2 === 0 && Math.fround(Number(`${down}e${Number(exactExp) - p + 1}`)) === ax) {
        digits = down;
        exponent = Number(exactExp);
      }
      break;
    }
  }
  const sign = x < 0 ? '-' : '';
  const scientific = `${digits[0]}${digits.length > 1 ? `.${digits.slice(1)}` : ''}e${exponent < 0 ? '-' : '+'}${String(Math.abs(exponent)).padStart(2, '0')}`;
  let fixed;
  if (exponent >= digits.length - 1) fixed = digits + '0'.repeat(exponent - digits.length + 1);
  else if (exponent >= 0) fixed = `${digits.slice(0, exponent + 1)}.${digits.slice(exponent + 1)}`;
  else fixed = `0.${'0'.repeat(-exponent - 1)}${digits}`;
  return sign + (fixed.length <= scientific.length ? fixed : scientific);
}

/**
 * mesh: readDrawnMesh's { positions, normals (vec4 each), info (uvec4: ptex, u bits, v bits),
 * tessVertices (uvec4: element, st, s bits, t bits), triangles, hasTexCoords }, and
 * approximate (a Uint8Array, 1 where the vertex is off the limit surface). Returns the bytes
 * (a Uint8Array; no Node API, so it runs in a browser too).
 */
export function encodePly(mesh, ascii = false) {
  const n = mesh.positions.length / 4, triangles = mesh.triangles.length / 3;
  const flags = mesh.approximate.some((a) => a !== 0), uv = mesh.hasTexCoords;
  let header = `ply\nformat ${ascii ? 'ascii' : 'binary_little_endian'} 1.0\ncomment limn-render: the triangles as drawn\n`;
  header += `element vertex ${n}\n`;
  for (const p of ['x', 'y', 'z', 'nx', 'ny', 'nz']) header += `property float ${p}\n`;
  header += 'property int ptex\nproperty float u\nproperty float v\n';
  if (uv) header += 'property float s\nproperty float t\n';
  if (flags) header += 'property uchar approximate\n';
  header += `element face ${triangles}\nproperty list uchar int vertex_indices\nend_header\n`;
  const infoFloats = new Float32Array(mesh.info.buffer, mesh.info.byteOffset, mesh.info.length);
  const tessFloats = new Float32Array(mesh.tessVertices.buffer, mesh.tessVertices.byteOffset, mesh.tessVertices.length);
  const { positions: P, normals: N } = mesh;
  if (ascii) {
    const lines = [header];
    for (let i = 0; i < n; i++) {
      const f = [P[4 * i], P[4 * i + 1], P[4 * i + 2], N[4 * i], N[4 * i + 1], N[4 * i + 2]].map(shortestFloat);
      f.push(String(mesh.info[4 * i] | 0), shortestFloat(infoFloats[4 * i + 1]), shortestFloat(infoFloats[4 * i + 2]));
      if (uv) f.push(shortestFloat(tessFloats[4 * i + 2]), shortestFloat(tessFloats[4 * i + 3]));
      if (flags) f.push(mesh.approximate[i] ? '1' : '0');
      lines.push(`${f.join(' ')}\n`);
    }
    const T = mesh.triangles;
    for (let t = 0; t < triangles; t++) lines.push(`3 ${T[3 * t]} ${T[3 * t + 1]} ${T[3 * t + 2]}\n`);
    return new TextEncoder().encode(lines.join('')); // ASCII only
  }
  const stride = (uv ? 44 : 36) + (flags ? 1 : 0);
  const head = new TextEncoder().encode(header);
  const out = new Uint8Array(head.length + n * stride + triangles * 13), view = new DataView(out.buffer);
  out.set(head);
  // Every float as the bits the GPU wrote.
  const PB = new Uint32Array(P.buffer, P.byteOffset, P.length), NB = new Uint32Array(N.buffer, N.byteOffset, N.length);
  let o = head.length;
  for (let i = 0; i < n; i++, o += stride) {
    for (let c = 0; c < 3; c++) {
      view.setUint32(o + 4 * c, PB[4 * i + c], true);
      view.setUint32(o + 12 + 4 * c, NB[4 * i + c], true);
    }
    // ptex, u, v and s, t as the GPU wrote their bits.
    for (let k = 0; k < 3; k++) view.setUint32(o + 24 + 4 * k, mesh.info[4 * i + k], true);
    if (uv) {
      view.setUint32(o + 36, mesh.tessVertices[4 * i + 2], true);
      view.setUint32(o + 40, mesh.tessVertices[4 * i + 3], true);
    }
    if (flags) out[o + stride - 1] = mesh.approximate[i] ? 1 : 0;
  }
  for (let t = 0; t < triangles; t++, o += 13) {
    out[o] = 3;
    for (let k = 0; k < 3; k++) view.setUint32(o + 1 + 4 * k, mesh.triangles[3 * t + k], true);
  }
  return out;
}
