#!/usr/bin/env node
// Validates glTF files (.gltf with its .bin and images, or .glb) with the Khronos glTF
// validator (npm `gltf-validator`, installed into .cache/npm by tools/setup --test; another install
// is named by GLTF_VALIDATOR=DIR/node_modules/gltf-validator). Prints every error (and, with
// -v, warnings), and exits 1 when any file has an error, 2 when it cannot run.
// Usage: tools/check/gltf-validate.js [-v] FILE...
'use strict';
const fs = require('fs');
const path = require('path');

const where = process.env.GLTF_VALIDATOR ||
  path.join(__dirname, '..', '..', '.cache', 'npm', 'node_modules', 'gltf-validator');
let validator;
try {
  validator = require(where);
} catch (e) {
  console.error(`gltf-validate: cannot load gltf-validator from ${where} (run tools/setup --test): ${e.message}`);
  process.exit(2);
}

const args = process.argv.slice(2);
const verbose = args[0] === '-v';
const files = verbose ? args.slice(1) : args;
if (files.length === 0) {
  console.error('usage: tools/check/gltf-validate.js [-v] FILE...');
  process.exit(2);
}

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const folder = path.dirname(file);
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    // Buffers and images named by relative URIs are read beside the file.
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.join(folder, decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const shown = report.issues.messages.filter((m) => m.severity === 0 || verbose);
  for (const m of shown) {
    const kind = ['error', 'warning', 'info', 'hint'][m.severity] || 'issue';
    console.log(`${file}: ${kind}: ${m.code} ${m.pointer || ''}: ${m.message}`);
  }
  const n = report.issues.numErrors;
  console.log(`${file}: ${n} errors, ${report.issues.numWarnings} warnings`);
  return n;
}

(async () => {
  let errors = 0;
  for (const f of files) {
    try {
      errors += await validate(f);
    } catch (e) {
      console.log(`${f}: error: ${e}`);
      errors += 1;
    }
  }
  process.exit(errors > 0 ? 1 : 0);
})();
