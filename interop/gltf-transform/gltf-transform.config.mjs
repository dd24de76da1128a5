// For the gltf-transform command-line tool: `gltf-transform COMMAND IN OUT --config
// gltf-transform.config.mjs` keeps MPEG_haptic_material (mpeg-haptic-material.js) beside every
// extension glTF-Transform itself knows. Needs @gltf-transform/extensions where this file lies.
import { ALL_EXTENSIONS } from "@gltf-transform/extensions";
import { MPEGHapticMaterial } from "./mpeg-haptic-material.js";

export default { extensions: [...ALL_EXTENSIONS, MPEGHapticMaterial] };
