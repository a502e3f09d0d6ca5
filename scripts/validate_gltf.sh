#!/usr/bin/env bash
# Runs the Khronos glTF validator (npm package gltf-validator, the official one compiled to
# JavaScript) over glTF files and fails when any has an error or a warning (infos and hints
# are printed with -v but do not fail). A manual check, not part of ctest: CI installs Debian
# packages only, and the validator is not packaged for Debian (docs/real-content.md).
#   npm install --prefix "$HOME/.cache/gltf-validator" gltf-validator     # once
#   scripts/validate_gltf.sh [-v] [FILE.glb|FILE.gltf ...]   (default: scenes/library/real/*.glb)
# GLTF_VALIDATOR_PREFIX overrides where it was installed.
set -euo pipefail
prefix=${GLTF_VALIDATOR_PREFIX:-$HOME/.cache/gltf-validator}
verbose=0
if [[ ${1:-} == -v ]]; then verbose=1; shift; fi
if [[ $# -eq 0 ]]; then
  cd "$(dirname "$0")/.."
  set -- scenes/library/real/*.glb
fi
if [[ ! -d $prefix/node_modules/gltf-validator ]]; then
  echo "validate_gltf.sh: gltf-validator is not installed under $prefix (npm install --prefix $prefix gltf-validator)" >&2
  exit 2
fi
NODE_PATH=$prefix/node_modules VERBOSE=$verbose node - "$@" <<'JS'
const validator = require('gltf-validator');
const fs = require('fs');
const path = require('path');
(async () => {
  let failed = 0;
  for (const file of process.argv.slice(2)) {
    const dir = path.dirname(file);
    const load = (uri) => new Promise((resolve, reject) => {
      try { resolve(new Uint8Array(fs.readFileSync(path.join(dir, decodeURIComponent(uri))))); }
      catch (e) { reject(e.toString()); }
    });
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)),
                                                 {uri: path.basename(file), externalResourceFunction: load});
    const n = report.issues;
    console.log(`${file}: ${n.numErrors} errors, ${n.numWarnings} warnings, ${n.numInfos} infos, ${n.numHints} hints`);
    const worst = process.env.VERBOSE === '1' ? 3 : 1;  // 0 error, 1 warning, 2 info, 3 hint
    for (const m of n.messages) {
      if (m.severity <= worst) console.log(`  ${['error', 'warning', 'info', 'hint'][m.severity]} ${m.code} at ${m.pointer || '/'}: ${m.message}`);
    }
    if (n.numErrors + n.numWarnings > 0) failed++;
  }
  process.exit(failed ? 1 : 0);
})();
JS
