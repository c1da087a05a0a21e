// Validates a .glb with the Khronos glTF-Validator (npm gltf-validator,
// pinned in graphics/web/package.json) and prints its counts and messages as
// JSON: node validate_gltf.js FILE.glb
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require(path.join(__dirname, '../../graphics/web/node_modules/gltf-validator'));

validator.validateBytes(new Uint8Array(fs.readFileSync(process.argv[2])), { maxIssues: 50 })
  .then((report) => {
    const messages = report.issues.messages.map((m) => `${m.severity} ${m.code} ${m.pointer || ''}: ${m.message}`);
    console.log(JSON.stringify({ errors: report.issues.numErrors, warnings: report.issues.numWarnings,
                                 infos: report.issues.numInfos, messages }));
  })
  .catch((error) => { console.log(JSON.stringify({ errors: 1, messages: [String(error)] })); });
