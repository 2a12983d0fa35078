// Validates glTF/GLB files with the Khronos glTF-Validator (npm package gltf-validator).
// usage: node validate.mjs NODE_MODULES_DIR FILE...
// Prints each file's counts and every message that is not an info or hint; exit status 0 when
// every file has zero errors and zero warnings, 1 otherwise, 77 when the validator is missing.
import { createRequire } from "node:module";
import { readFile } from "node:fs/promises";
import path from "node:path";

const [modules, ...files] = process.argv.slice(2);
let validator;
try {
    validator = createRequire(path.join(path.resolve(modules), "noop.js"))("gltf-validator");
} catch (error) {
    console.log(`gltf-validator is not installed under ${modules} (scripts/test installs it)`);
    process.exit(77);
}

let failed = false;
for (const file of files) {
    const bytes = new Uint8Array(await readFile(file));
    const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        externalResourceFunction: (uri) =>
            readFile(path.join(path.dirname(file), decodeURIComponent(uri))).then(
                (data) => new Uint8Array(data)),
    });
    const issues = report.issues;
    console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
                `${issues.numInfos} infos, ${issues.numHints} hints (validator ${report.validatorVersion})`);
    for (const message of issues.messages)
        if (message.severity <= 1)
            console.log(`  ${message.severity === 0 ? "error" : "warning"} ${message.code} at ` +
                        `${message.pointer ?? "-"}: ${message.message}`);
    failed ||= issues.numErrors > 0 || issues.numWarnings > 0;
}
process.exit(failed ? 1 : 0);
