// A workspace asset's patches merged into one mesh, as a 3-D artist's "join objects" does (Blender's
// Ctrl-J): every node's primitives moved, in the scene's frame, into the first node's mesh, each
// keeping its own visual material; the other nodes removed. glTF-Transform's own `join` leaves
// Sandpaper's patches apart (each has a material of its own), so this is the merge it does not do.
// Usage: node merge_meshes.mjs EXTENSION_FILE IN OUT
import path from "node:path";
import { NodeIO } from "@gltf-transform/core";
import { prune, transformPrimitive } from "@gltf-transform/functions";

const [extensionFile, input, output] = process.argv.slice(2);
const { MPEGHapticMaterial } = await import(path.resolve(extensionFile));
const io = new NodeIO().registerExtensions([MPEGHapticMaterial]);
const doc = await io.read(input);
const nodes = doc.getRoot().getDefaultScene().listChildren().filter((n) => n.getMesh());
const [first, ...rest] = nodes;
const into = first.getMesh();
let moved = 0;
for (const node of rest) {
  // Positions into the first node's frame: the nodes are translated only (Sandpaper's export).
  const [a, b] = [first.getTranslation(), node.getTranslation()];
  const m = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, b[0] - a[0], b[1] - a[1], b[2] - a[2], 1];
  for (const prim of node.getMesh().listPrimitives()) {
    transformPrimitive(prim, m);
    into.addPrimitive(prim);
    moved++;
  }
  node.dispose();
}
await doc.transform(prune());
await io.write(output, doc);
console.log(`${moved} primitives of ${rest.length} nodes moved into ${first.getName()}'s mesh, ` +
            `${doc.getRoot().listMeshes().length} mesh(es) left`);
