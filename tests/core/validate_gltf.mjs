// Runs the Khronos glTF validator (npm package gltf-validator, see the repository's package.json) on
// each file named on the command line. Prints one JSON object: {"files": [{file, errors, warnings,
// infos, hints, messages: [{code, severity, pointer, message}]}]}. Exit status 0 when no file has
// errors, 1 when one has, 2 when the validator could not run.
// Usage: node tests/core/validate_gltf.mjs scene.gltf [more.gltf ...]
import { readFile } from 'node:fs/promises';
import path from 'node:path';
import validator from 'gltf-validator';

const severityNames = ['error', 'warning', 'info', 'hint'];

async function validate(file) {
    const folder = path.dirname(path.resolve(file));
    const bytes = new Uint8Array(await readFile(file));
    const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 1000,
        writeTimestamp: false,
        // External buffers and images are read from the file's folder, as Bounce's loader does.
        externalResourceFunction: async (uri) => new Uint8Array(await readFile(path.join(folder, decodeURIComponent(uri)))),
    });
    const issues = report.issues;
    return {
        file,
        errors: issues.numErrors,
        warnings: issues.numWarnings,
        infos: issues.numInfos,
        hints: issues.numHints,
        messages: issues.messages.map((m) => ({
            code: m.code,
            severity: severityNames[m.severity] ?? String(m.severity),
            pointer: m.pointer,
            message: m.message,
        })),
    };
}

try {
    const files = process.argv.slice(2);
    if (files.length === 0) {
        console.error('usage: node validate_gltf.mjs file.gltf [...]');
        process.exit(2);
    }
    const results = [];
    for (const file of files) results.push(await validate(file));
    console.log(JSON.stringify({ files: results }, null, 2));
    process.exit(results.some((r) => r.errors > 0) ? 1 : 0);
} catch (e) {
    console.error(`validate_gltf: ${e.stack ?? e}`);
    process.exit(2);
}
