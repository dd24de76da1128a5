// Checks glTF assets that `sandpaper export --format gltf` wrote (ctest gltf.validate, docs/GLTF.md):
// Khronos' glTF-Validator for the glTF 2.0 core (schema and rules, any error fails), then ajv for the
// MPEG_haptic_material extension's structure (schema/MPEG_haptic_material.sandpaper-check.schema.json)
// and Sandpaper's extras (schema/sandpaper-extras.schema.json), and the indices between them.
// Before the real files, a broken copy of the first one must be caught by both checks, so that a
// validator that passes everything fails this test instead.
// Usage: node validate.mjs FILE.gltf...   Exit 0: all valid; 1: an error; 77: packages not installed.
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { createRequire } from 'node:module';

const here = dirname(fileURLToPath(import.meta.url));
if (!existsSync(join(here, 'node_modules', 'ajv')) || !existsSync(join(here, 'node_modules', 'gltf-validator'))) {
  console.log('SKIPPED: tests/gltf/node_modules is absent; run `npm ci` in tests/gltf (tools/install-deps.sh does)');
  process.exit(77);
}
const require = createRequire(import.meta.url);
const validator = require('gltf-validator');
const Ajv = require('ajv');

const ajv = new Ajv({ allErrors: true, strict: false });
const ext = JSON.parse(readFileSync(join(here, 'schema', 'MPEG_haptic_material.sandpaper-check.schema.json'), 'utf8'));
ajv.addSchema(ext);
const extras = ajv.compile(JSON.parse(readFileSync(join(here, 'schema', 'sandpaper-extras.schema.json'), 'utf8')));
const gltfLevel = ajv.getSchema(ext.$id + '#/definitions/gltfLevel');
const meshLevel = ajv.getSchema(ext.$id + '#/definitions/meshLevel');

// Core glTF 2.0: the validator's errors (severity 0), as lines.
async function coreErrors(bytes, name) {
  const format = name.endsWith('.glb') ? 'glb' : 'gltf';
  const report = await validator.validateBytes(new Uint8Array(bytes), { uri: name, format, maxIssues: 0 });
  const issues = report.issues;
  const lines = issues.messages.filter((m) => m.severity === 0).map((m) => `${m.code} at ${m.pointer}: ${m.message}`);
  return { lines, warnings: issues.numWarnings, infos: issues.numInfos };
}

// The extension and Sandpaper's extras: problems, as lines.
function extensionErrors(asset) {
  const out = [];
  const say = (where, errors) => errors.forEach((e) => out.push(`${where}${e.instancePath}: ${e.message}`));
  const top = asset.extensions?.MPEG_haptic_material;
  if (!(asset.extensionsUsed || []).includes('MPEG_haptic_material')) out.push('extensionsUsed lacks MPEG_haptic_material');
  if (!gltfLevel(top)) say('/extensions/MPEG_haptic_material', gltfLevel.errors);
  const materials = top?.materials || [];
  materials.forEach((m, i) => {
    if (!extras(m?.extras?.sandpaper)) say(`/extensions/MPEG_haptic_material/materials/${i}/extras/sandpaper`, extras.errors);
    (m?.vibrotactileTexture || []).forEach((t, j) => {
      if (!(t?.texture?.index < (asset.textures || []).length))
        out.push(`/extensions/MPEG_haptic_material/materials/${i}/vibrotactileTexture/${j}/texture/index: no such texture`);
    });
  });
  (asset.meshes || []).forEach((mesh, i) => {
    const m = mesh.extensions?.MPEG_haptic_material;
    if (m === undefined) return out.push(`/meshes/${i}: no MPEG_haptic_material (every exported mesh is a patch)`);
    if (!meshLevel(m)) say(`/meshes/${i}/extensions/MPEG_haptic_material`, meshLevel.errors);
    else if (m.hapticMaterialIndex >= materials.length)
      out.push(`/meshes/${i}/extensions/MPEG_haptic_material/hapticMaterialIndex: no such haptic material`);
  });
  return out;
}

// The asset's JSON: the file, or a .glb's JSON chunk (glTF 2.0 section 4.4: 12-byte header, then
// the chunk's length and type, then the chunk).
function assetJson(name, bytes) {
  const b = Buffer.from(bytes);
  if (!name.endsWith('.glb')) return JSON.parse(b.toString('utf8'));
  if (b.toString('latin1', 0, 4) !== 'glTF' || b.readUInt32LE(16) !== 0x4E4F534A) throw new Error(`${name}: not a .glb`);
  return JSON.parse(b.toString('utf8', 20, 20 + b.readUInt32LE(12)));
}

async function check(name, bytes) {
  const core = await coreErrors(bytes, name);
  const extension = extensionErrors(assetJson(name, bytes));
  return { core, extension };
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node validate.mjs FILE.gltf...');
  process.exit(2);
}

// The control: one error for each check, planted in a copy of the first file.
const broken = JSON.parse(readFileSync(files[0], 'utf8'));
delete broken.accessors[0].min;                                       // core: POSITION needs min and max
delete broken.meshes[0].extensions.MPEG_haptic_material.hapticMaterialIndex;  // extension: required
broken.extensions.MPEG_haptic_material.materials[0].extras.sandpaper.compiled_max_lateral_force_N = '1.7 N';  // extras: a number
const control = await check('control.gltf', Buffer.from(JSON.stringify(broken)));
if (control.core.lines.length === 0 || control.extension.length < 2) {
  console.error('FAIL: the checks did not catch errors planted in a copy of ' + files[0] + ':', JSON.stringify(control));
  process.exit(1);
}
console.log(`control: planted errors caught (${control.core.lines.length} by glTF-Validator, ${control.extension.length} by ajv)`);

let failed = false;
for (const file of files) {
  const { core, extension } = await check(file, readFileSync(file));
  const bad = core.lines.length + extension.length;
  console.log(`${file}: glTF-Validator ${core.lines.length} errors, ${core.warnings} warnings, ${core.infos} infos; ` +
              `MPEG_haptic_material + extras (ajv) ${extension.length} errors`);
  for (const line of [...core.lines, ...extension]) console.log('  ' + line);
  failed ||= bad > 0;
}
process.exit(failed ? 1 : 0);
