// limn's WebGPU runtime: load a .limn container, render it with limn-render's passes and the
// same shaders (generated WGSL). Works in a browser (navigator.gpu) and in Node (npm `webgpu`,
// see node_device.mjs); no bundler needed.
export { loadLimn } from './chunks.mjs';
export { parseContainer, LimnError } from './container.mjs';
export { Renderer, SHADES } from './renderer.mjs';
export { encodePly } from './ply.mjs';
export { buildTessellation } from './tessellation.mjs';
export { frameCamera, viewMatrix, projectionMatrix } from './camera.mjs';
export { loadShader } from './shaders.mjs';
