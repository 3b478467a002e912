// Runs the Khronos glTF validator over every .gltf and .glb in a folder (the assets the tests wrote) and
// fails on any error or warning: the tests' files must be valid glTF, not only what clipblur accepts.
// Usage: node validate.js FOLDER MIN_COUNT
'use strict';
const fs = require('fs');
const path = require('path');
let validator;
try {
    validator = require('gltf-validator');
} catch (e) {
    console.log('SKIP: gltf-validator is not installed (run npm ci in tests/gltf)');
    process.exit(77);
}

const folder = process.argv[2];
const minCount = Number(process.argv[3] || 1);
const files = fs.existsSync(folder)
    ? fs.readdirSync(folder).filter((f) => f.endsWith('.gltf') || f.endsWith('.glb')).sort()
    : [];
if (files.length < minCount) {
    console.error(`expected at least ${minCount} assets in ${folder}, found ${files.length}`);
    process.exit(1);
}

async function validate(file) {
    const full = path.join(folder, file);
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(full)), {
        uri: file,
        externalResourceFunction: (uri) =>
            Promise.resolve(new Uint8Array(fs.readFileSync(path.resolve(folder, decodeURIComponent(uri))))),
    });
    const { numErrors, numWarnings } = report.issues;
    const problems = report.issues.messages.filter((m) => m.severity <= 1);
    for (const m of problems) console.error(`${file}: ${m.pointer || ''}: ${m.code}: ${m.message}`);
    console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings`);
    return numErrors + numWarnings;
}

(async () => {
    let bad = 0;
    for (const f of files) bad += (await validate(f)) > 0 ? 1 : 0;
    console.log(`${files.length} assets, ${bad} with errors or warnings`);
    process.exit(bad === 0 ? 0 : 1);
})();
