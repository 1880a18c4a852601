#!/usr/bin/env node
// Validates one .glb or .gltf file with the Khronos glTF validator
// (npm gltf-validator, pinned in package.json) and prints its report as JSON.
//
// Usage: node tools/node/validate-gltf.js FILE [--allow-hints]
// Exit codes: 0 no errors, no warnings (and no hints unless --allow-hints);
//             1 the report has an error or a warning (or a hint);
//             2 usage, unreadable file, or the validator refused the input.
// Infos (e.g. UNSUPPORTED_EXTENSION for KHR_draco_mesh_compression, whose
// payload this validator cannot decode) never fail. External resources are
// refused, so a file that needs one fails with the validator's IO error
// instead of passing unchecked. The report has no timestamp: it is
// deterministic for a given file.
'use strict';

const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

function usage(message) {
  process.stderr.write(`validate-gltf: ${message}\nusage: node validate-gltf.js FILE [--allow-hints]\n`);
  process.exit(2);
}

async function main() {
  const args = process.argv.slice(2);
  const allowHints = args.includes('--allow-hints');
  const files = args.filter((a) => a !== '--allow-hints');
  if (files.length !== 1) usage('expected exactly one file');
  const file = files[0];
  let bytes;
  try {
    bytes = fs.readFileSync(file);
  } catch (e) {
    usage(`cannot read ${file}: ${e.message}`);
  }
  let report;
  try {
    report = await validator.validateBytes(new Uint8Array(bytes), {
      uri: path.basename(file),
      maxIssues: 0,  // report every issue
      writeTimestamp: false,
      externalResourceFunction: (uri) => Promise.reject(new Error(`external resource '${uri}' refused`)),
    });
  } catch (e) {
    usage(`the validator refused ${file}: ${e}`);
  }
  process.stdout.write(JSON.stringify(report, null, 2) + '\n');
  const issues = report.issues;
  const failing = issues.numErrors + issues.numWarnings + (allowHints ? 0 : issues.numHints);
  if (failing > 0) {
    process.stderr.write(
        `validate-gltf: ${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
        `${issues.numHints} hints${allowHints ? ' (allowed)' : ''}\n`);
    process.exit(1);
  }
}

main();
