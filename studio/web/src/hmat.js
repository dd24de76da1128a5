// Syntax highlighting for Sandpaper's material (.hmat) and workspace (.hws) files: a CodeMirror 6
// stream parser over the language's tokens (schema/LANGUAGE.md): comments, strings, numbers, units,
// statement keywords, options, and the names of force laws.
import { StreamLanguage } from "@codemirror/language";

const statements = new Set([
  "material", "describes", "like", "roughness", "grating", "heightmap", "pattern", "quantize", "spring", "damper",
  "size", "extrapolate", "force", "physics", "energy", "family", "alias", "licence", "license", "deprecated", "overrides", "accept",
  "source", "workspace", "patch", "viscosity", "stickiness", "slipperiness", "softness", "springiness", "bumpiness",
]);
const options = new Set([
  "period", "hill", "amplitude", "orientation", "smoothing", "repeat", "invert", "channel", "sampling", "depth",
  "press", "valley", "offset", "feature", "pixel", "kernel", "refilter", "seed", "count", "bits", "budget", "refill",
  "replaced-by", "at", "stiffness", "damping", "axes", "mass",
]);
const kinds = new Set(["measurement", "standard", "publication", "derived", "by-ear", "bars", "grid", "perlin", "noise", "stripes"]);
const units = new Set([
  "m", "cm", "mm", "um", "in", "N", "mN", "gf", "ozf", "ju", "pu", "N/m", "N/mm", "N*s/m", "deg", "%", "kg", "g", "s",
  "ms", "J", "mJ", "W", "mW", "m/s", "mm/s",
]);

export const hmatLanguage = StreamLanguage.define({
  name: "sandpaper",
  token(stream) {
    if (stream.eatSpace()) return null;
    if (stream.match("#")) {
      stream.skipToEnd();
      return "comment";
    }
    if (stream.match(/^"(?:[^"\\]|\\.)*"?/)) return "string";
    if (stream.match(/^[+-]?\d+(\.\d+)?([eE][+-]?\d+)?/)) return "number";
    if (stream.match("%")) return "unit";
    if (stream.match(/^[{}]/)) return "brace";
    if (stream.match(/^[;,]/)) return "punctuation";
    const word = stream.match(/^[A-Za-z_][A-Za-z0-9_\-/*]*/);
    if (word) {
      const w = word[0];
      if (statements.has(w)) return "keyword";
      if (options.has(w)) return "propertyName";
      if (units.has(w)) return "unit";
      if (kinds.has(w)) return "atom";
      if (/^[A-Z]/.test(w)) return "typeName";  // force laws: Wave, AntiViscous, ...
      return "variableName";
    }
    stream.next();
    return null;
  },
  languageData: { commentTokens: { line: "#" } },
});
