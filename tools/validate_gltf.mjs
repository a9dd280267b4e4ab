// Validates a .glb/.gltf file with the Khronos glTF validator and prints its report as JSON.
// Exit status: 0 when the report has no errors, 1 when it has, 2 when the file cannot be read.
// Usage: node tools/validate_gltf.mjs FILE
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');

const file = process.argv[2];
if (!file) {
  console.error('usage: node validate_gltf.mjs FILE');
  process.exit(2);
}
let bytes;
try {
  bytes = new Uint8Array(readFileSync(file));
} catch (e) {
  console.error(`cannot read ${file}: ${e.message}`);
  process.exit(2);
}
const report = await validator.validateBytes(bytes, { uri: file, maxIssues: 100 });
console.log(JSON.stringify({
  errors: report.issues.numErrors,
  warnings: report.issues.numWarnings,
  infos: report.issues.numInfos,
  messages: report.issues.messages,
}));
process.exit(report.issues.numErrors === 0 ? 0 : 1);
