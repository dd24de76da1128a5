// MPEG_haptic_material (ISO/IEC 23090-14's haptics in glTF) for glTF-Transform: the root list of
// haptic materials and each mesh's `hapticMaterialIndex`. Without it, glTF-Transform drops both (an
// extension it does not know is not written), and the haptic textures, which no visual material
// uses, are pruned. Registered, a haptic material keeps its name, extras (Sandpaper's
// `extras.sandpaper`: the force rule and its numbers, docs/GLTF.md) and every field as written; its
// textures are held as Texture references, so they survive dedup and prune, and are written back
// wherever the pipeline puts images (embedded, beside the asset, in a .glb). A haptic texture is
// heights, not colours: a transform that re-encodes or resizes it (optimize, png, webp, resize, ...)
// would lose them, so while this extension is registered its image stays as read (with a warning).
//
//   import { MPEGHapticMaterial } from "sandpaper-gltf-transform-mpeg-haptic-material";
//   const io = new NodeIO().registerExtensions([MPEGHapticMaterial]);
import { Extension, ExtensionProperty, PropertyType, RefList, TextureChannel, TextureInfo } from "@gltf-transform/core";

const NAME = "MPEG_haptic_material";

// A texture a haptic material names: where it was listed ("vibrotactileTexture", "stiffness", ...),
// the fields written beside it ("type", ...), and the texture with its sampling.
export class HapticTexture extends ExtensionProperty {
  static EXTENSION_NAME = NAME;
  init() {
    this.extensionName = NAME;
    this.propertyType = "HapticTexture";
    this.parentTypes = ["HapticMaterial"];
  }
  getDefaults() {
    return Object.assign(super.getDefaults(), {
      list: "", fields: {}, texture: null, textureInfo: new TextureInfo(this.graph, "textureInfo"),
    });
  }
  getList() { return this.get("list"); }
  setList(list) { return this.set("list", list); }
  getFields() { return this.get("fields"); }
  setFields(fields) { return this.set("fields", fields); }
  getTexture() { return this.getRef("texture"); }
  // Heights in one channel: glTF-Transform's texture functions ask each texture's edge which it uses.
  setTexture(texture) { return this.setRef("texture", texture, { channels: TextureChannel.R }); }
  // The sampling (wrap, filters, texCoord), as for any glTF texture.
  getTextureInfo() { return this.getRef("textureInfo"); }
}

// One entry of extensions.MPEG_haptic_material.materials: its fields other than the textures, kept
// as written, and its textures in the order they were listed.
export class HapticMaterial extends ExtensionProperty {
  static EXTENSION_NAME = NAME;
  init() {
    this.extensionName = NAME;
    this.propertyType = "HapticMaterial";
    this.parentTypes = [PropertyType.MESH];
  }
  getDefaults() {
    return Object.assign(super.getDefaults(), { fields: {}, textures: new RefList() });
  }
  getFields() { return this.get("fields"); }
  setFields(fields) { return this.set("fields", fields); }
  listTextures() { return this.listRefs("textures"); }
  addTexture(t) { return this.addRef("textures", t); }
}

// A texture reference in a haptic material: an array entry that is an object with a `texture`
// object holding an `index`.
function isTextureEntry(v) {
  return v && typeof v === "object" && !Array.isArray(v) && v.texture && typeof v.texture.index === "number";
}

export class MPEGHapticMaterial extends Extension {
  extensionName = NAME;
  static EXTENSION_NAME = NAME;
  // Read before the visual materials, which use the same textures as their colour: a texture written
  // as a file is named by its first user, and as a haptic texture it takes the asset's name
  // (corduroy.png), where as a base colour it would be baseColor.png in every asset of a folder.
  prereadTypes = [PropertyType.MATERIAL];
  prewriteTypes = [PropertyType.MESH];

  createHapticMaterial(name = "") { return new HapticMaterial(this.document.getGraph(), name); }
  createHapticTexture() { return new HapticTexture(this.document.getGraph()); }
  listHapticMaterials() { return Array.from(this.properties).filter((p) => p instanceof HapticMaterial); }

  // Before the visual materials and meshes are read, with the textures already read: the haptic materials.
  preread(context) {
    const json = context.jsonDoc.json;
    const defs = json.extensions?.[NAME]?.materials || [];
    const textureDefs = json.textures || [];
    this._read = defs.map((def) => {
      const m = this.createHapticMaterial(def.name || "");
      if (def.extras) m.setExtras(def.extras);
      const fields = {};
      for (const [key, value] of Object.entries(def)) {
        if (key === "name" || key === "extras") continue;
        if (Array.isArray(value) && value.length && value.every(isTextureEntry)) {
          for (const entry of value) {
            const t = this.createHapticTexture().setList(key);
            const { texture: info, ...rest } = entry;
            t.setFields(rest);
            const source = textureDefs[info.index]?.source;
            if (source !== undefined) {
              t.setTexture(context.textures[source]);
              context.setTextureInfo(t.getTextureInfo(), info);
              this._keepAsRead(context.textures[source]);
            }
            m.addTexture(t);
          }
        } else {
          fields[key] = value;
        }
      }
      return m.setFields(fields);
    });
    return this;
  }

  // Puts back a haptic texture's image, type and name whenever a transform changes them: the
  // texture's bytes are 16-bit heights whose every bit the force rule reads (docs/GLTF.md).
  _keepAsRead(texture) {
    if (!texture || (this._kept ||= new Set()).has(texture)) return;
    this._kept.add(texture);
    const image = texture.getImage(), mimeType = texture.getMimeType(), uri = texture.getURI();
    let warned = false, restoring = false;
    texture.addEventListener("change", ({ attribute }) => {
      if (restoring) return;
      const now = { image: texture.getImage(), mimeType: texture.getMimeType(), uri: texture.getURI() };
      if (now.image === image && now.mimeType === mimeType && (now.uri === uri || !/\.(webp|jpe?g|avif|ktx2)$/i.test(now.uri))) return;
      if (!warned) {
        warned = true;
        this.document.getLogger().warn(
          `${NAME}: haptic texture "${uri || texture.getName() || "(embedded)"}" kept as read (${mimeType}): ` +
          `it holds heights, and re-encoding or resizing it (${attribute} changed) would lose them.`);
      }
      restoring = true;
      texture.set("image", image).set("mimeType", mimeType).set("uri", uri);
      restoring = false;
    });
  }

  // Meshes are read after prereading: each names its haptic material by index.
  read(context) {
    (context.jsonDoc.json.meshes || []).forEach((meshDef, i) => {
      const index = meshDef.extensions?.[NAME]?.hapticMaterialIndex;
      if (typeof index === "number" && this._read?.[index]) context.meshes[i].setExtension(NAME, this._read[index]);
    });
    return this;
  }

  // Textures and materials are written before the meshes, so that the textures have indices.
  prewrite(context) {
    const materials = this.listHapticMaterials();
    this._index = new Map();
    this._defs = materials.map((m, i) => {
      this._index.set(m, i);
      const def = context.createPropertyDef(m);
      Object.assign(def, structuredClone(m.getFields()));
      for (const t of m.listTextures()) {
        const texture = t.getTexture();
        if (!texture) continue;
        const info = context.createTextureInfoDef(texture, t.getTextureInfo());
        (def[t.getList()] ||= []).push({ ...structuredClone(t.getFields()), texture: info });
      }
      return def;
    });
    return this;
  }

  write(context) {
    if (!this._defs?.length) return this;
    const json = context.jsonDoc.json;
    for (const mesh of this.document.getRoot().listMeshes()) {
      const m = mesh.getExtension(NAME);
      if (!m) continue;
      const def = json.meshes[context.meshIndexMap.get(mesh)];
      def.extensions ||= {};
      def.extensions[NAME] = { hapticMaterialIndex: this._index.get(m) };
    }
    json.extensions ||= {};
    json.extensions[NAME] = { materials: this._defs };
    return this;
  }
}
