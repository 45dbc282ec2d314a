#!/usr/bin/env node
// Validates glTF 2.0 files (.glb, or .gltf with embedded data: URIs) with the Khronos
// glTF-Validator (npm package gltf-validator, pinned in package.json / package-lock.json and
// installed by scripts/setup.sh into tests/tools/node_modules).
//   node tests/tools/validate_gltf.js FILE...
// Prints, per file, one line "FILE: errors E warnings W infos I hints H" and then every message.
// Exit status: 0 every file has zero errors and zero warnings, 1 some file has errors or
// warnings, 2 usage, 3 the validator is not installed (run scripts/setup.sh).
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
  validator = require(path.join(__dirname, 'node_modules', 'gltf-validator'));
} catch (e) {
  console.error('validate_gltf: error: ' + path.join(__dirname, 'node_modules') +
                ': gltf-validator is not installed; run scripts/setup.sh (npm ci in tests/tools)');
  process.exit(3);
}

async function main(files) {
  if (files.length === 0) {
    console.error('usage: validate_gltf.js FILE...');
    return 2;
  }
  let bad = false;
  for (const file of files) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      maxIssues: 0,
      // Only data: URIs are expected; anything external is reported as missing.
      externalResourceFunction: (uri) => Promise.reject(new Error('external resource ' + uri)),
    });
    const i = report.issues;
    console.log(`${file}: errors ${i.numErrors} warnings ${i.numWarnings} infos ${i.numInfos} ` +
                `hints ${i.numHints} (validator ${report.validatorVersion})`);
    const severity = ['error', 'warning', 'info', 'hint'];
    for (const m of i.messages)
      console.log(`  ${severity[m.severity]} ${m.code} ${m.pointer || ''}: ${m.message}`);
    if (i.numErrors > 0 || i.numWarnings > 0) bad = true;
  }
  return bad ? 1 : 0;
}

main(process.argv.slice(2)).then((code) => process.exit(code), (e) => {
  console.error('validate_gltf: error: ' + e);
  process.exit(1);
});
