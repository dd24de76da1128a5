#pragma once
// The three kinds of file the studio edits, told apart by extension as the CLI tells them: a
// material (.hmat), a workspace of patches (.hws), a 3-D scene (.hsc).
#include <filesystem>
#include <optional>

namespace sandpaper::studio {

enum class FileKind { Material, Workspace, Scene };

// nullopt for any other extension.
inline std::optional<FileKind> file_kind(const std::filesystem::path& file) {
  const auto ext = file.extension();
  if (ext == ".hmat") return FileKind::Material;
  if (ext == ".hws") return FileKind::Workspace;
  if (ext == ".hsc") return FileKind::Scene;
  return std::nullopt;
}

// As the API and the page name it ("kind" in /api/current).
inline const char* kind_name(FileKind k) {
  return k == FileKind::Material ? "material" : k == FileKind::Workspace ? "workspace" : "scene";
}

inline const char* kind_extension(FileKind k) {
  return k == FileKind::Material ? ".hmat" : k == FileKind::Workspace ? ".hws" : ".hsc";
}

// For messages: "a material (.hmat), a workspace (.hws) or a scene (.hsc)".
inline const char* kinds_text() { return "a material (.hmat), a workspace (.hws) or a scene (.hsc)"; }

}  // namespace sandpaper::studio
