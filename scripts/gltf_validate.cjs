// Validate glTF files with the Khronos glTF-Validator (npm gltf-validator, package.json).
// Usage: node scripts/gltf_validate.cjs FILE...  Prints one JSON report per line:
// {"file", "validator", "errors", "warnings", "infos", "hints", "codes": {code: count}}.
const fs = require("fs");
const validator = require("gltf-validator");

(async () => {
  for (const file of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      maxIssues: 1000,
    });
    const codes = {};
    for (const message of report.issues.messages) {
      codes[message.code] = (codes[message.code] || 0) + 1;
    }
    console.log(
      JSON.stringify({
        file,
        validator: report.validatorVersion,
        errors: report.issues.numErrors,
        warnings: report.issues.numWarnings,
        infos: report.issues.numInfos,
        hints: report.issues.numHints,
        codes,
      }),
    );
  }
})();
