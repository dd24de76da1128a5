// The scene's triangles as the studio sent them (GET /api/scene: metres, the scene's frame, which is
// three.js' own: x right, y up, z toward the viewer), one mesh with a group per run of triangles on
// one surface, each surface in its colour (the colours of `sandpaper preview SCENE`).
import { BufferAttribute, BufferGeometry, DoubleSide, Mesh, MeshLambertMaterial } from "three";

export function sceneMesh(g) {
  const geometry = new BufferGeometry();
  geometry.setAttribute("position", new BufferAttribute(Float32Array.from(g.positions_m), 3));
  geometry.setIndex(new BufferAttribute(Uint32Array.from(g.triangles), 1));
  // Runs of one surface become draw groups: a box's six faces are six groups, a ball one.
  const surfaces = g.triangle_surfaces;
  for (let t = 0; t < surfaces.length;) {
    let end = t + 1;
    while (end < surfaces.length && surfaces[end] === surfaces[t]) end++;
    geometry.addGroup(3 * t, 3 * (end - t), surfaces[t]);
    t = end;
  }
  geometry.computeVertexNormals();
  geometry.computeBoundingSphere();
  // Both sides drawn, so a plane seen from below or a room from outside still shows; the hand is
  // only pressed on the side a surface is felt from (dummy.js).
  const materials = g.surfaces.map((s) => new MeshLambertMaterial({ color: s.colour, side: DoubleSide }));
  const mesh = new Mesh(geometry, materials);
  mesh.name = "scene";
  return mesh;
}

export function disposeMesh(mesh) {
  if (!mesh) return;
  mesh.geometry.dispose();
  for (const m of mesh.material) m.dispose();
}
