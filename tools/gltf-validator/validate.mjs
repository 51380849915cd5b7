// SPDX-License-Identifier: MIT
// Checks GLB files with the Khronos glTF validator (npm package gltf-validator): prints every issue
// found as "file: SEVERITY CODE at POINTER: message" and a one-line count per file, and exits 1 when
// any file has an error or a warning (infos and hints are printed, not counted), 2 on bad usage or an
// unreadable file. A GLB carries its buffers and images, so nothing outside the file is loaded.
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import path from 'node:path';

const require = createRequire(import.meta.url);
const severities = ['ERROR', 'WARNING', 'INFO', 'HINT'];

async function check(file, validator) {
    const bytes = new Uint8Array(await readFile(file));
    const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 0, // every issue
        externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri} in a GLB`)),
    });
    for (const m of report.issues.messages)
        console.log(`${file}: ${severities[m.severity] ?? m.severity} ${m.code} at ${m.pointer ?? '/'}: ${m.message}`);
    const { numErrors, numWarnings, numInfos, numHints } = report.issues;
    console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints` +
                ` (validator ${report.validatorVersion})`);
    return numErrors + numWarnings;
}

async function main(files) {
    if (files.length === 0) {
        console.error('usage: node validate.mjs FILE.glb...');
        return 2;
    }
    let validator;
    try {
        validator = require('gltf-validator');
    } catch (e) {
        console.error(`gltf-validator is not installed next to ${import.meta.url}: run scripts/gltf_validator.sh`);
        return 2;
    }
    let bad = 0;
    for (const f of files) {
        try {
            bad += await check(f, validator);
        } catch (e) {
            console.error(`${f}: cannot validate: ${e.message}`);
            return 2;
        }
    }
    return bad > 0 ? 1 : 0;
}

process.exitCode = await main(process.argv.slice(2));
