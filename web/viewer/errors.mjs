// The viewer's error list in the panel (id "errors"), keyed so that a later success clears its
// own error, and what an exception says in words.
import { LimnError } from '../src/index.mjs';
import { ViewerError } from './gpu.mjs';

const errors = new Map();
const $ = (id) => document.getElementById(id);
export function showError(key, message) {
  errors.set(key, message);
  renderErrors();
}
export function clearError(key) { if (errors.delete(key)) renderErrors(); }
/** Clears every error whose key starts with `prefix`. */
export function clearErrors(prefix) { for (const k of [...errors.keys()]) if (k.startsWith(prefix)) clearError(k); }
function renderErrors() {
  const box = $('errors');
  box.replaceChildren(...[...errors.values()].map((m) => Object.assign(document.createElement('div'), { className: 'error', textContent: m })));
  document.body.dataset.errors = errors.size;
}
// A LimnError names the chunk it is about ('chunk TBLS: ...'); its other kinds say only what.
const GENERIC = ['capability', 'usage', 'input', 'output'];
export function describe(e) {
  if (e instanceof LimnError) return GENERIC.includes(e.where) ? e.detail : e.message;
  return e instanceof ViewerError ? e.message : `${e.name ?? 'Error'}: ${e.message ?? e}`;
}
