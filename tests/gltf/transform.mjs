// ctest gltf.transform (run_transform.sh): glTF-Transform, from the npm registry, reads each asset,
// deduplicates and prunes it (what `gltf-transform optimize`-style pipelines do) and writes it as a
// .gltf with its images and buffers as files beside it: once with Sandpaper's MPEG_haptic_material
// extension registered (EXTENSION, a copy of interop/gltf-transform/mpeg-haptic-material.js) into
// OUT/script-with/, once without into OUT/script-without/. run_transform.sh then compiles both.
// Usage: node transform.mjs EXTENSION OUT ASSET...
import path from "node:path";
import { NodeIO } from "@gltf-transform/core";
import { dedup, prune } from "@gltf-transform/functions";

const [extensionFile, out, ...assets] = process.argv.slice(2);
const { MPEGHapticMaterial } = await import(path.resolve(extensionFile));
for (const asset of assets) {
  const name = path.basename(asset);
  for (const [folder, io] of [["script-with", new NodeIO().registerExtensions([MPEGHapticMaterial])], ["script-without", new NodeIO()]]) {
    const doc = await io.read(asset);
    await doc.transform(dedup(), prune());
    await io.write(path.join(out, folder, name), doc);
    const haptic = doc.getRoot().listExtensionsUsed().map((e) => e.extensionName).includes("MPEG_haptic_material");
    console.log(`${folder.replace("script-", "")} the extension: ${name} -> ${path.join(out, folder, name)} (${doc.getRoot().listTextures().length} textures` +
                `${haptic ? ", MPEG_haptic_material kept" : ""})`);
  }
}
