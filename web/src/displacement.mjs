// Texture displacement with paper 000's seam fix (4.5), as limn-render does it
// (lib/render/subdivision_pass.cpp, subdivision_draw.cpp): the tessellation vertices are evaluated
// once by a compute pass (surface_eval.comp), moved along their limit normals by
// scale * (average sample - mid) (displace.comp; adaptive_displace.comp for the view-adaptive
// tessellation), given the displaced surface's normals (displaced_normals.comp;
// adaptive_displaced_normals.comp), and the draw only fetches them (surface_fetch.vert).
// The seam fix: every copy of a point on a UV seam samples the map at the UVs the point has in
// every face around it, in increasing face order, so the copies move by the same bits and the
// displaced surface stays watertight; without it each copy samples its own chart and cracks open
// (the paper's Figure 4).
import { LimnError } from './container.mjs';
import { TESS_ONE, PtexMap } from './tessellation.mjs';
import { ROW_GROUPS } from './adaptive.mjs';

const f32 = Math.fround;

/** The map as displace.comp reads it: width, height, then channel 0 of each texel (float bits). */
export function mapWords(map) {
  const w = new Uint32Array(2 + map.width * map.height);
  w[0] = map.width;
  w[1] = map.height;
  new Float32Array(w.buffer, 8).set(map.values.subarray(0, map.width * map.height));
  return w;
}

/**
 * The colour texture as surface.frag reads it: width, height, then sRGB RGBA8 texels packed
 * R | G << 8 | B << 16 | 0xff << 24 (subdivision_pass.cpp textureWords); one white texel without one.
 * texture: {width, height, rgb (Float32Array of width*height*3 values in 0..1, as decoded)}.
 */
export function textureWords(texture) {
  if (!texture) return new Uint32Array([1, 1, 0xffffffff]);
  const n = texture.width * texture.height, w = new Uint32Array(2 + n);
  w[0] = texture.width;
  w[1] = texture.height;
  const byte = (v) => Math.round(Math.min(Math.max(v, 0), 1) * 255);
  for (let i = 0; i < n; i++) {
    w[2 + i] = (byte(texture.rgb[3 * i]) | (byte(texture.rgb[3 * i + 1]) << 8) | (byte(texture.rgb[3 * i + 2]) << 16) | 0xff000000) >>> 0;
  }
  return w;
}

/** A map's GPU buffer (4 bytes a texel) must fit WebGPU's 128 MiB storage-buffer binding. */
export function checkMapSize(option, map) {
  const bytes = 8 + 4 * map.width * map.height;
  if (bytes > 128 * 2 ** 20) {
    throw new LimnError(`${option}: a ${map.width}x${map.height} map needs ${(bytes / 2 ** 20).toFixed(1)} MiB on the GPU, over WebGPU's ` +
      '128 MiB storage-buffer limit; scale it down (at most about 5792x5792)', 'input');
  }
}

/**
 * renderer.cpp's check: an EXR-like map times --displace-scale must stay within the 1e18 that
 * positions may reach (mesh.cpp), or the image comes out blank.
 */
export function checkDisplacement(d) {
  checkMapSize('--displace', d.map);
  let far = 0;
  for (const v of d.map.values) far = Math.max(far, Math.abs((v - d.mid) * d.scale));
  if (!(far <= 1e18)) {
    throw new LimnError(`--displace: the map's values times --displace-scale move the surface by up to ${far.toPrecision(3)}, ` +
      "beyond the 1e18 that the GPU's float arithmetic carries", 'input');
  }
}

// subdivision_draw.cpp's sideUVsOf: the UVs a fixed-grid vertex samples the map at, from its
// element's seam record (paper 000, Figures 8 and 9): a corner every face around it, an edge
// point both sides' UVs interpolated along the edge, an interior point its own face's.
function sideUVsOf(seams, element, st, out) {
  const r = seams.records, rf = new Float32Array(r.buffer, r.byteOffset, r.length), base = 24 * element;
  const S = st & 0xffff, T = st >>> 16;
  const s0 = S === 0, s1 = S === TESS_ONE, t0 = T === 0, t1 = T === TESS_ONE;
  const s = S / TESS_ONE, t = T / TESS_ONE;
  const uv = seams.uvs;
  if ((s0 || s1) && (t0 || t1)) {
    const k = s0 ? (t0 ? 0 : 3) : (t0 ? 1 : 2);
    const first = r[base + 8 + 2 * k], count = r[base + 9 + 2 * k];
    for (let i = 0; i < count; i++) out.push(uv[2 * (first + i)], uv[2 * (first + i) + 1]);
    return count;
  }
  let edge = -1, x = 0;
  if (t0) { edge = 0; x = s; } else if (s1) { edge = 1; x = t; } else if (t1) { edge = 2; x = 1 - s; } else if (s0) { edge = 3; x = 1 - t; }
  if (edge >= 0) {
    const first = r[base + 16 + 2 * edge], sides = r[base + 17 + 2 * edge];
    for (let i = 0; i < sides; i++) {
      const a = 2 * (first + 2 * i), b = a + 2;
      out.push(f32(uv[a] + x * (uv[b] - uv[a])), f32(uv[a + 1] + x * (uv[b + 1] - uv[a + 1])));
    }
    return sides;
  }
  const c = (k) => [rf[base + 2 * k], rf[base + 2 * k + 1]];
  const [c0, c1, c2, c3] = [c(0), c(1), c(2), c(3)];
  const w0 = (1 - s) * (1 - t), w1 = s * (1 - t), w2 = s * t, w3 = (1 - s) * t;
  out.push(f32(w0 * c0[0] + w1 * c1[0] + w2 * c2[0] + w3 * c3[0]), f32(w0 * c0[1] + w1 * c1[1] + w2 * c2[1] + w3 * c3[1]));
  return 1;
}

// seams.h: the most distinct UVs at one point (the readers' limit), and the UVs one 128 MiB
// storage buffer holds.
const MAX_POINT_UVS = 4096, MAX_SEAM_UVS = (128 * 2 ** 20) / 8;

/**
 * lib/seams/seams.cpp's computeSeams, for a container without a SEAM chunk (limn-render computes
 * them too): per element, its corners' UVs in their own face, every distinct UV of each corner
 * in the faces around it, and per edge the distinct (start, end) UV pairs of the faces along it,
 * in increasing face order. Returns the chunk's layout ({records, uvs, uvCount}).
 */
export function computeSeams(mesh, uvs, tables) {
  const R = 2 ** (tables.depth + 1); // one step finer than the finest element: edge midpoints are lattice points
  const ptex = new PtexMap({ ...mesh, uvs }, R);
  const E = tables.patchCount + tables.irregularCount;
  const records = new Uint32Array(Math.max(E, 1) * 24), rf = new Float32Array(records.buffer), out = [];
  const CU = [0, 1, 1, 0], CV = [0, 0, 1, 1];
  const same = (x, y) => x[0] === y[0] && x[1] === y[1];
  const f2 = (uv) => [f32(uv[0]), f32(uv[1])];
  // A point's charts (in face order) and its distinct float UVs. A base vertex's are made once
  // (seams.cpp): from each of its elements they would cost its whole ring, and the distinct UVs
  // of a vertex with a seam between every two faces their square per element.
  const describe = (charts) => {
    const distinct = [], seen = new Set();
    for (const c of charts) {
      const uv = f2(c.uv), key = `${uv[0]},${uv[1]}`; // String(-0) is "0": -0 and 0 merge, as === does
      if (!seen.has(key)) { seen.add(key); distinct.push(uv); }
    }
    if (distinct.length > MAX_POINT_UVS) {
      throw new LimnError(`a vertex has ${distinct.length} different UVs in the faces around it, more than the ` +
        `${MAX_POINT_UVS} the displacement's seam fix averages`);
    }
    return { charts, distinct };
  };
  const baseVertices = new Map();
  const at = (p, U, V) => {
    const key = ptex.key(p, U, V);
    if (ptex.kindOf(key) !== 1) return describe(ptex.charts(p, U, V));
    let d = baseVertices.get(key);
    if (!d) { d = describe(ptex.charts(p, U, V)); baseVertices.set(key, d); }
    return d;
  };
  // The UVs stay within one storage buffer (WebGPU's 128 MiB), checked as they grow.
  const reserve = (more) => {
    if (out.length + more > MAX_SEAM_UVS) {
      throw new LimnError(`the seams need more than ${MAX_SEAM_UVS} UVs (128 MiB, one GPU storage buffer): each element at a ` +
        "vertex carries all of the vertex's different UVs, and some vertex has UV seams between many of its faces");
    }
  };
  // The UV of `face` in a point's charts (face order; the last of equal faces, as a scan would).
  const uvIn = (charts, face) => {
    let lo = 0, hi = charts.length;
    while (lo < hi) { const mid = (lo + hi) >> 1; if (charts[mid].face <= face) lo = mid + 1; else hi = mid; }
    return lo > 0 && charts[lo - 1].face === face ? f2(charts[lo - 1].uv) : [0, 0];
  };
  const add = (e, p, u0, v0, size) => {
    const base = 24 * e, U0 = Math.trunc(u0 * R), V0 = Math.trunc(v0 * R), W = Math.trunc(size * R);
    const corner = (k) => [U0 + CU[k] * W, V0 + CV[k] * W];
    for (let k = 0; k < 4; k++) {
      const own = f2(ptex.ownUV(p, u0 + CU[k] * size, v0 + CV[k] * size));
      rf[base + 2 * k] = own[0];
      rf[base + 2 * k + 1] = own[1];
      const { distinct } = at(p, ...corner(k));
      reserve(distinct.length);
      records[base + 8 + 2 * k] = out.length;
      records[base + 9 + 2 * k] = distinct.length;
      for (const uv of distinct) out.push(uv);
    }
    for (let k = 0; k < 4; k++) {
      const [Ua, Va] = corner(k), [Ub, Vb] = corner((k + 1) % 4);
      const ends = [at(p, Ua, Va).charts, at(p, Ub, Vb).charts];
      const sides = [];
      records[base + 16 + 2 * k] = out.length;
      for (const side of at(p, (Ua + Ub) / 2, (Va + Vb) / 2).charts) { // the faces along the edge
        const pair = ends.map((list) => uvIn(list, side.face));
        if (sides.some((x) => same(x[0], pair[0]) && same(x[1], pair[1]))) continue;
        sides.push(pair);
        reserve(2);
        out.push(pair[0], pair[1]);
      }
      records[base + 17 + 2 * k] = sides.length;
    }
  };
  const pw = tables.patches, pf = new Float32Array(pw.buffer, pw.byteOffset, pw.length);
  const qw = tables.irregular, qf = new Float32Array(qw.buffer, qw.byteOffset, qw.length);
  for (let i = 0; i < tables.patchCount; i++) add(i, pw[24 * i + 16], pf[24 * i + 17], pf[24 * i + 18], pf[24 * i + 19]);
  for (let i = 0; i < tables.irregularCount; i++) add(tables.patchCount + i, qw[8 * i + 4], qf[8 * i + 5], qf[8 * i + 6], qf[8 * i + 7]);
  return { records: records.subarray(0, E * 24), uvs: Float32Array.from(out.flat()), uvCount: out.length };
}

/**
 * The SEAM records as adaptive_displace.comp's ElementSeams reads them: own[4], then cornerFirst,
 * cornerCount, edgeFirst, edgeSides as uvec4s (the chunk interleaves each first with its count).
 */
export function seamGpuRecords(seams) {
  const r = seams.records, out = new Uint32Array(Math.max(r.length, 24));
  for (let base = 0; base < r.length; base += 24) {
    out.set(r.subarray(base, base + 8), base);
    for (let k = 0; k < 4; k++) {
      out[base + 8 + k] = r[base + 8 + 2 * k];
      out[base + 12 + k] = r[base + 9 + 2 * k];
      out[base + 16 + k] = r[base + 16 + 2 * k];
      out[base + 20 + k] = r[base + 17 + 2 * k];
    }
  }
  return out;
}

/**
 * The fixed grids' displacement plan (prepareSubdivision with a DisplacementPlan): per vertex
 * the range of UVs it samples, and the triangles around its point (all copies of a seam point
 * together, in index order) for the displaced normals. With smooth UVs (a tessellation built
 * with the FVSF surface, `tables` given), the UVs around a point are its smooth UVs in every face
 * containing it (subdivision_draw.cpp with ChartUVs::sides).
 */
export function fixedDisplacementPlan(tess, seams, seamFix, tables = null) {
  const n = tess.vertexCount, v = tess.vertices, vf = new Float32Array(v.buffer, v.byteOffset, v.length);
  const sideRanges = new Uint32Array(Math.max(n, 1) * 2), uvs = [];
  // Smooth UVs (the tessellation's smoothCharts): the point's smooth UV in every face around it.
  const smoothSides = (i) => {
    const e = v[4 * i], st = v[4 * i + 1], P = tables.patchCount;
    const w = e < P ? tables.patches.subarray(24 * e + 16, 24 * e + 20) : tables.irregular.subarray(8 * (e - P) + 4, 8 * (e - P) + 8);
    const f = new Float32Array(w.buffer, w.byteOffset, 4), R = 2 ** tables.depth;
    const U = (f[1] + ((st & 0xffff) / 32768) * f[3]) * R, V = (f[2] + ((st >>> 16) / 32768) * f[3]) * R;
    // An element's centre (a single cell's fan) lies inside one face: its own UV.
    const sides = Number.isInteger(U) && Number.isInteger(V) ? tess.smoothCharts.sides(w[0], U, V) : [[vf[4 * i + 2], vf[4 * i + 3]]];
    for (const uv of sides) uvs.push(uv[0], uv[1]);
    return sides.length;
  };
  for (let i = 0; i < n; i++) {
    const first = uvs.length / 2;
    const count = seamFix && tess.smoothCharts ? smoothSides(i)
      : seamFix ? sideUVsOf(seams, v[4 * i], v[4 * i + 1], uvs) : (uvs.push(vf[4 * i + 2], vf[4 * i + 3]), 1);
    sideRanges[2 * i] = first;
    sideRanges[2 * i + 1] = count;
  }
  const geometry = tess.geometry, indices = tess.indices;
  const count = new Uint32Array(n + 1);
  for (const idx of indices) count[geometry[idx] + 1]++;
  for (let i = 0; i < n; i++) count[i + 1] += count[i];
  const incident = new Uint32Array(Math.max(indices.length, 1)), fill = count.slice(0, n);
  for (let k = 0; k < indices.length; k++) incident[fill[geometry[indices[k]]]++] = Math.floor(k / 3);
  const incidentRanges = new Uint32Array(Math.max(n, 1) * 2);
  for (let i = 0; i < n; i++) {
    const g = geometry[i];
    incidentRanges[2 * i] = count[g];
    incidentRanges[2 * i + 1] = count[g + 1] - count[g];
  }
  return { sideRanges, sideUVs: Float32Array.from(uvs.length ? uvs : [0, 0]), incidentRanges, incident };
}

// The evaluation dispatches of the view-adaptive tessellation read how many vertices the frame
// emitted from the scan's totals (dispatchWorkgroupsIndirect); their header holds the capacity.
function indirectPass(r, pipeline, bindGroup, fields, label) {
  const p = r.pushGroup(pipeline);
  r.pushData.set([r.adaptiveData.capV, ROW_GROUPS * 64, 0, 0, ...fields], p.offset / 4);
  r.passes.push({ pipeline, bindGroup, push: p.group, indirect: true, label, pushOffset: p.offset });
}

/**
 * subdivision_pass.cpp's --eval compute: surface_eval.comp evaluates every tessellation vertex once
 * into evalPositions/evalNormals/evalInfo (for displacement, and for the wireframe's positions).
 */
export async function addComputeEvaluation(r, compute, group) {
  const { buffers: b } = r, { tables } = r.surface;
  const n = r.adaptive ? r.adaptiveData.capV : Math.max(r.tess.vertexCount, 1);
  Object.assign(b, {
    evalPositions: r.empty('evaluated positions', n * 16),
    evalNormals: r.empty('evaluated normals', n * 16),
    evalInfo: r.empty('evaluated ptex', n * 16),
  });
  const evalPass = await compute('surface_eval.comp');
  const evalGroup = group(evalPass, 0, [b.vertices, b.patches, b.irregular, b.limits, b.tessVertices, b.evalPositions, b.evalNormals, b.evalInfo]);
  if (r.adaptive) indirectPass(r, evalPass, evalGroup, [tables.patchCount], 'evaluate surface');
  else r.dispatch(evalPass, evalGroup, r.tess.vertexCount, [tables.patchCount], 'evaluate surface');
}

// subdivision_pass.cpp with a displacement, after addComputeEvaluation: displace and displaced
// normals (fixed grids: displace.comp, displaced_normals.comp over the CPU-built plan;
// view-adaptive: adaptive_displace*.comp over what this frame emitted).
export async function addDisplacementPasses(r, compute, group, plan) {
  const { s, buffers: b } = r, { tables } = r.surface, d = s.displace;
  const n = r.adaptive ? r.adaptiveData.capV : Math.max(r.tess.vertexCount, 1);
  Object.assign(b, {
    displaced: r.empty('displaced positions', n * 16),
    displacedNormals: r.empty('displaced normals', n * 16),
    map: r.buffer('displacement map', mapWords(d.map)),
  });
  const [displacePass, normalsPass] = await Promise.all((r.adaptive
    ? ['adaptive_displace.comp', 'adaptive_displaced_normals.comp']
    : ['displace.comp', 'displaced_normals.comp']).map(compute));
  const f32 = (x) => new Uint32Array(new Float32Array([x]).buffer)[0];
  if (r.adaptive) {
    b.seamElements = r.buffer('seam elements', seamGpuRecords(r.seams));
    b.seamUVs = r.buffer('seam UVs', r.seams.uvs);
    indirectPass(r, displacePass, group(displacePass, 0, [b.evalPositions, b.evalNormals, b.tessVertices, b.seamElements, b.seamUVs, b.map, b.displaced]),
      [f32(d.scale), f32(d.mid), d.seamFix ? 1 : 0, r.smooth ? 1 : 0], 'displace'); // smooth: the emitted UV inside
    indirectPass(r, normalsPass, group(normalsPass, 0, [b.vertices, b.patches, b.irregular, b.limits, b.tessVertices, b.elements, b.map, b.displacedNormals]),
      [tables.patchCount, f32(d.scale), f32(d.mid)], 'displaced normals');
    return;
  }
  Object.assign(b, {
    sideRanges: r.buffer('displacement sample ranges', plan.sideRanges),
    sideUVs: r.buffer('displacement sample UVs', plan.sideUVs),
    incidentRanges: r.buffer('incident ranges', plan.incidentRanges),
    incident: r.buffer('incident triangles', plan.incident),
  });
  const count = r.tess.vertexCount;
  r.dispatch(displacePass, group(displacePass, 0, [b.evalPositions, b.evalNormals, b.sideRanges, b.sideUVs, b.map, b.displaced]),
    count, [f32(d.scale), f32(d.mid)], 'displace');
  r.dispatch(normalsPass, group(normalsPass, 0, [b.displaced, b.triangles, b.incidentRanges, b.incident, b.displacedNormals]), count, [], 'displaced normals');
}
