// TypeScript declarations of limn's WebGPU runtime (src/index.mjs).
/// <reference types="@webgpu/types" />

/** Bad input (or a usage or capability refusal); `where` names the chunk, header or option. */
export class LimnError extends Error {
  readonly where: string;
  readonly detail: string;
}

export interface Chunk { type: string; version: number; payload: Uint8Array; offset: number }
/** The container's framing (formats/limn.md sections 2-4); throws LimnError. */
export function parseContainer(bytes: Uint8Array | ArrayBuffer): Chunk[];

export interface StencilTable { rows: number; start: Uint32Array; index: Uint32Array; weight: Float32Array | null }
export interface Level { first: number; facePoints: number; edgePoints: number; vertexPoints: number; regularPatches: number; irregularFaces: number; count: number }
export interface SchemeOptions { boundary: number; creaseMethod: number; triangles: number; fvar: number }
export interface Tables {
  /** levels: 0..depth + irregularLevels (TBLS v3: levels refined only under the irregular faces). */
  depth: number; irregularLevels: number; uniform: boolean; options: SchemeOptions; totalVertices: number; levels: Level[];
  facePoints: StencilTable[]; edgePoints: StencilTable[]; vertexPoints: StencilTable[];
  /** 24 words a patch: cv[16], ptex, u0, v0, size, level | boundary << 8 | crease << 16, sharpness, 2 pad;
   *  after the patchCount patches, the irregular faces' quadtrees as limn-render uploads them. */
  patchCount: number; patches: Uint32Array;
  /** 8 words an irregular face: corner[4], ptex, u0, v0, size; after the irregularCount faces, the leaves. */
  irregularCount: number; irregular: Uint32Array;
  limitCount: number; limitPosition: StencilTable; limitTangent1: StencilTable; limitTangent2: StencilTable;
  limitVertex: Uint32Array; limitFlags: Uint32Array;
}
export interface Mesh { vertexCount: number; faceCount: number; positions: Float64Array; faceOffsets: Uint32Array; faceVertices: Uint32Array; faceSizes: Uint32Array }
export interface Surface {
  mesh: Mesh;
  uvs: { values: Float64Array; indices: Uint32Array } | null;
  tags: { boundary: number | null; fvar: number | null; creaseMethod: number | null; triangles: number | null;
    creases: { v0: number; v1: number; sharpness: number }[]; corners: { vertex: number; sharpness: number }[]; holes: Uint32Array } | null;
  material: { baseColorFactor: number[]; textureFormat: string; texture: Uint8Array } | null;
  classification: object | null;
  tables: Tables;
  seams: { records: Uint32Array; uvs: Float32Array; uvCount: number } | null;
  /** FVSF: the smooth face-varying UV surface (per-ptex quadtree nodes, 36 floats an element), or null. */
  fvarSurface: { depth: number; ptexCount: number; nodes: Uint32Array; records: Float32Array; elementCount: number } | null;
}
/** Reads MESH, FVUV, TAGS, MATL, CLSF, TBLS (v1 to v4), SEAM and FVSF, checking every count and index; BLND is refused. */
export function loadLimn(bytes: Uint8Array | ArrayBuffer): Surface;

export type Shade = 'lit' | 'normal' | 'uv' | 'levels' | 'texture';
export const SHADES: Record<Shade, number>;
export type Vec3 = [number, number, number];
export interface ViewSpec { azimuthDeg?: number; elevationDeg?: number; fovDeg?: number; zUp?: boolean; eye?: Vec3; target?: Vec3; up?: Vec3 }
/** limn-render's settings, by its option names (--size, --samples, --shade, --edge-pixels, --tess, ...). */
export interface RenderSettings {
  width?: number; height?: number; samples?: 1 | 4; sampleShading?: boolean; shade?: Shade;
  /** View-adaptive segments of about this many pixels (limn-render's default 4); 0: the fixed grids. */
  edgePixels?: number; tess?: number; view?: ViewSpec;
  /** --max-error: pixels between the drawn chords and the limit surface, at most (default 0.1);
   *  0: segments of about edgePixels. */
  maxError?: number;
  /** --interior-error: the maxError allowed where a piece faces the eye (every sample's normal
   *  within 70 degrees of the view ray; the outline keeps maxError); 0 (default): maxError everywhere. */
  interiorError?: number;
  /** --pixel-normals: view-adaptive, shade 'lit': the limit surface's normal at each pixel of a
   *  smooth patch instead of normals interpolated across the triangle; not with wire, displace or
   *  meshOut (those draw as without). */
  pixelNormals?: boolean;
  lightAzimuthDeg?: number; lightElevationDeg?: number; color?: Vec3; background?: Vec3;
  /** --texture (or a MATL texture): values 0..1 as decoded, 3 a texel, rows top to bottom; with shade 'texture'. */
  texture?: ImageRGB;
  /** --displace: the seam UVs from the container's SEAM chunk (limn-seams), else computed. */
  displace?: Displacement;
  /** 'triangles': limn-render --wire-triangles, the edges of every triangle drawn; 'outlines':
   *  --wire, the patches' and faces' outlines (drawn on the fixed grids). */
  wire?: 'triangles' | 'outlines';
  /** --mesh-out: view-adaptive, every triangle of an element that draws some is emitted (no
   *  shared slots), as limn-render evaluates them for its --mesh-out; then call drawnMesh(). */
  meshOut?: boolean;
}
export interface ImageRGB { width: number; height: number; rgb: Float32Array }
export interface Displacement {
  /** Channel 0 of the height map, rows top to bottom (v = 0 is the bottom row). */
  map: { width: number; height: number; values: Float32Array };
  /** --displace-scale (world units per unit of map value) and --displace-mid (the value meaning zero). */
  scale: number; mid: number;
  /** false: --no-seam-fix (each face samples its own UV; cracks open at UV seams). */
  seamFix: boolean;
}
export class Renderer {
  static create(device: GPUDevice, surface: Surface, settings: RenderSettings): Promise<Renderer>;
  /** Moves the camera (same conventions and framing as limn-render). */
  setView(view: ViewSpec): void;
  /** Records and submits one frame: upload, the compute passes, the draw, the copy to readback. */
  frame(): void;
  /** The last frame's RGBA8 pixels, rows top to bottom. */
  pixels(): Promise<Uint8Array>;
  triangleCount(): number;
  /** Triangles the last frame drew (view-adaptive: read back from the GPU). */
  drawnTriangles(): Promise<number>;
  destroy(): void;
  readonly timings: { js: number };
}

export interface Tessellation { vertices: Uint32Array; vertexCount: number; indices: Uint32Array; triangleLevels: Uint32Array; geometry: number[] }
export function buildTessellation(mesh: Mesh & { uvs: Surface['uvs'] }, tables: Tables, cap: number, splitUVSeams?: boolean): Tessellation;

export interface Camera { eye: Vec3; target: Vec3; up: Vec3; fovYRad: number; nearPlane: number; farPlane: number }
export function frameCamera(spec: ViewSpec, bounds: { min: Vec3; max: Vec3; sphereRadius: number; hull: Vec3[] }, aspect: number): Camera;
export function viewMatrix(camera: Camera): number[];
export function projectionMatrix(camera: Camera, aspect: number): number[];
/** The generated WGSL of one of limn's shaders, by its GLSL name ('surface.vert'). */
export function loadShader(name: string): Promise<string>;
/** The surface as drawn, read back (what limn-render --mesh-out writes). */
export interface DrawnMesh {
  /** xyzw per vertex (displaced when displaced). */
  positions: Float32Array;
  /** xyz_ per vertex. */
  normals: Float32Array;
  /** Per vertex: ptex face, then the bits of u and v in it (floats), one word unused. */
  info: Uint32Array;
  /** Per vertex: element, s | t << 16 (1/32768), the bits of the texture UV (floats). */
  tessVertices: Uint32Array;
  /** 1 where the vertex is not on the limit surface (drawn bilinear near an extraordinary corner). */
  approximate: Uint8Array;
  /** 3 indices a triangle. */
  triangles: Uint32Array;
  /** Whether the mesh has texture coordinates (the PLY's s t). */
  hasTexCoords: boolean;
}
export interface Renderer {
  /** The drawn surface as limn-render --mesh-out writes it (view-adaptive: create with settings.meshOut). */
  drawnMesh(): Promise<DrawnMesh>;
}
/** limn-render's --mesh-out PLY, the same bytes: binary little-endian, or ASCII. */
export function encodePly(mesh: DrawnMesh, ascii?: boolean): Uint8Array;
