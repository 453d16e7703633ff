// SPDX-License-Identifier: MIT
// Runs the Khronos glTF validator (npm package gltf-validator) on .gltf/.glb files and prints one
// JSON line per file: {file, errors, warnings, infos, messages}. Exit status 1 when any file has an
// error. The package is looked up in CLEAVE_GLTF_VALIDATOR_DIR (a folder where
// `npm install gltf-validator` was run, for example the build folder's npm/, where the set-up puts
// it), else in the usual places. See docs/cleave-split.md.
'use strict';
const fs = require('fs');
const path = require('path');

function loadValidator() {
  const dir = process.env.CLEAVE_GLTF_VALIDATOR_DIR;
  const paths = dir ? [dir, path.join(dir, 'node_modules')] : undefined;
  return require(require.resolve('gltf-validator', paths ? { paths } : undefined));
}

async function main() {
  const validator = loadValidator();
  let failed = 0;
  for (const file of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), { maxIssues: 200 });
    const issues = report.issues;
    const messages = issues.messages
      .filter((m) => m.severity <= 1)  // errors and warnings
      .map((m) => `${m.code} ${m.pointer || ''} ${m.message}`);
    console.log(JSON.stringify({ file, errors: issues.numErrors, warnings: issues.numWarnings,
                                 infos: issues.numInfos, messages }));
    if (issues.numErrors > 0) failed++;
  }
  process.exit(failed ? 1 : 0);
}

main().catch((error) => {
  console.error(`gltf-validate: ${error && error.message ? error.message : error}`);
  process.exit(2);
});
