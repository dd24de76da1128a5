#pragma once
// Validation of Sandpaper's TOML data files (calibration maps, device files, levels, knowledge)
// against the JSON Schemas in schema/files/*.schema.json. The schemas are standard JSON Schema
// (draft-07) so editors (taplo, VS Code) can check files as they are written; this validator
// implements the subset those schemas use and reports each violation at its file:line:col.
//
// Subset: $ref (to #/definitions/...), type, properties, required, additionalProperties (bool),
// enum, const, minimum, exclusiveMinimum, maximum, items, minItems, maxItems, anyOf, and one
// Sandpaper keyword, "x-dimension": the value is a quantity string ("382 gf") whose unit has that
// dimension ("length", "force", ...; schema/LANGUAGE.md's units).
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

namespace sandpaper::schema {

struct SchemaViolation {
  std::string key;      // dotted path to the offending value, e.g. "force.x.newtons_per_command_unit"
  int line = 0;         // 1-based position in the TOML file; 0 if unknown (a missing key)
  int column = 0;
  std::string message;  // what is wrong and what is expected
};

// Names of the shipped schemas: "map", "device", "levels", "force-jnd", "believability", "groups".
std::vector<std::string> file_schema_names();
// The JSON text of a shipped schema; throws std::out_of_range for an unknown name.
std::string_view file_schema_text(std::string_view name);
// Violations of `doc` against shipped schema `name`, in document order; empty if valid.
// Throws std::out_of_range for an unknown schema name.
std::vector<SchemaViolation> validate_file(const toml::table& doc, std::string_view name);

}  // namespace sandpaper::schema
