// The viewer's files: a file dropped anywhere on the page, or chosen with the pickers, goes to
// `openFile` (a model) or `openMap` (an image, as the chosen kind).
const $ = (id) => document.getElementById(id);

export function attachFiles(openFile, openMap) {
  let depth = 0;
  const hint = $('drop-hint');
  document.addEventListener('dragenter', (e) => { e.preventDefault(); depth++; hint.hidden = false; });
  document.addEventListener('dragleave', () => { if (--depth <= 0) { depth = 0; hint.hidden = true; } });
  document.addEventListener('dragover', (e) => e.preventDefault());
  document.addEventListener('drop', (e) => {
    e.preventDefault();
    depth = 0;
    hint.hidden = true;
    const file = e.dataTransfer?.files?.[0];
    if (file) openFile(file);
  });
  $('open-model').addEventListener('change', (e) => { const f = e.target.files[0]; if (f) openFile(f); e.target.value = ''; });
  $('open-map').addEventListener('change', (e) => { const f = e.target.files[0]; if (f) openMap(f, f.name, $('map-kind').value); e.target.value = ''; });
}
