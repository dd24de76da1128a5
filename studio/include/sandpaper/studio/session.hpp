#pragma once
// What the studio has open: a folder, one file in it (a material, a workspace or a 3-D scene), its
// text as edited (saved or not), and the last program that compiled, which is what plays (a scene is
// felt in the page's 3-D Dummy mode instead, through its SceneView). Every method is called
// from the HTTP threads and serialised by the session's own mutex; none touches the servo thread
// except through LiveLoop's non-blocking hand-over (docs/STUDIO.md).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/http/local_server.hpp"
#include "sandpaper/compiler/parameters.hpp"
#include "sandpaper/schema/workspace_program.hpp"
#include "sandpaper/studio/file_kind.hpp"
#include "sandpaper/studio/live_loop.hpp"
#include "sandpaper/studio/scene_view.hpp"

namespace sandpaper::studio {

// A request the studio refuses, with the HTTP status to answer and a message saying how to fix it.
using RequestError = http::RequestError;

class Session {
 public:
  // `root`: the folder (canonical); the process's working directory is `root`, so a material's
  // relative image paths resolve as they do for the CLI run from there. `preview_dir`: where preview
  // pictures are rendered (a private temporary folder).
  Session(const compiler::Compiler& compiler, LiveLoop& loop, std::filesystem::path root,
          std::filesystem::path preview_dir);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // The .hmat, .hws and .hsc files in the folder, 8 levels deep, at most 2000: {"files": [relative paths,
  // sorted], "not_listed": [{"file", "why"}], "unsaved": [files with edits not yet saved]}, the
  // second for names that are not UTF-8 (shown with U+FFFD), which a request could not name.
  nlohmann::json files() const;
  // Opens `relative` (confined to the folder), compiles and plays it. The file left keeps its unsaved
  // edits here, and opening it again brings them back ("restored_unsaved": true) rather than the
  // disk's text: switching files never drops a designer's text. So does a recovery copy that a
  // stopped studio left beside the file, when it differs from the file ("recovered": its name). RequestError 403 outside the
  // folder, 404 missing, 413 too large, 400 not a .hmat, .hws or .hsc; 501 a scene in a studio built
  // without SANDPAPER_SHAPES (SceneView::built()).
  nlohmann::json open(const std::string& relative);
  // The open file: {"file", "kind": "material"|"workspace"|"scene", "text", "text_version", "saved": bool,
  // "version", ...}, and "recovered": {"copy", "saved_text"} while its text is a recovery copy's
  // (keep_unsaved()) not yet saved, "saved_text" being the file's text on disk.
  nlohmann::json current() const;
  // What every page is told with each state event, so that a change made anywhere (this page, another
  // tab, the HTTP API) reaches them all: {"file", "text_version" (rises with every change of the
  // text), "saved", "compiles", "version" (of the program that text compiled to, when it did), "kind",
  // "scene_version" (of the last scene that compiled: rises with each, 0 before any)}.
  nlohmann::json document_state() const;

  // POST /api/compile: compiles `text` as a material, as `sandpaper compile --json` would; plays nothing.
  nlohmann::json compile_only(const std::string& text) const;
  // The editor's text changed: compile it; when it compiles, it becomes what plays (hot swap) and its
  // preview is rendered; when not, the last good program keeps playing. Returns the compile's JSON
  // plus "parameters", "version" (of the playing program) and "playing_is_current".
  nlohmann::json update(const std::string& text);
  // POST /api/parameter: sets one number in the text (only its characters change) and updates.
  // RequestError 400 for an unknown name or unit, 409 while the text does not compile.
  nlohmann::json set_parameter(const std::string& name, double value, const std::string& unit);
  // Writes the text to the open file atomically (temporary file + rename). Returns {"saved", "bytes"}.
  nlohmann::json save();
  // POST /api/new: creates `relative` (a .hmat, .hws or .hsc name inside the folder, in a folder that
  // exists, not yet a file) with a starting text that compiles (a material felt on the library's
  // reference texture; an empty workspace; a ball on a floor), then opens it; the file left keeps its unsaved edits.
  // RequestError 403 outside the folder, 400 another extension, 404 no such folder, 409 it exists.
  nlohmann::json create(const std::string& relative);
  // POST /api/save-as: writes the text to `relative` (as create() checks it) and makes that the open
  // file; the file it came from stays as it is on disk.
  nlohmann::json save_as(const std::string& relative);
  // POST /api/language: what `sandpaper lsp` answers an editor for the open text at (line, character)
  // (0-based; character in UTF-16 units, as the page's editor counts): `feature` "completion",
  // "hover" or "definition", by the language server's own functions (editors/lsp/include/sandpaper/lsp/features.hpp), as
  // LSP JSON. RequestError 400 for another feature or a position outside the text.
  nlohmann::json language(const std::string& feature, int line, int character) const;

  // When the studio stops (no request may run any more): every file with unsaved edits, the open one
  // and those left, has its text written beside it as recovery_path(file), atomically, for open() to
  // offer next time; a recovery copy offered and since saved or undone is removed. One entry a file
  // with unsaved edits: its name, the copy's name (relative to the folder) or why it could not be
  // written, and the text.
  struct Unsaved {
    std::string file, copy, error, text;
  };
  std::vector<Unsaved> keep_unsaved();
  // ".NAME.recovered" beside `file` (hidden, and not a .hmat or .hws, so never listed or compiled).
  static std::filesystem::path recovery_path(const std::filesystem::path& file);

  // Workspaces: the canvas' view ({"name", "size_mm", "patches": [{index, source, name, centre_mm,
  // size_mm, compiled_max_lateral_force_N, compiled_roughness}]}), and moving or resizing patch `index` (mm), which
  // rewrites its numbers in the text and updates. RequestError 409 when the open file is a material.
  nlohmann::json workspace() const;
  nlohmann::json place_patch(int index, double x_mm, double y_mm, double width_mm, double height_mm);

  // Scenes (docs/STUDIO.md, "Scenes in 3-D"): the open scene's geometry for the page to draw
  // (SceneView::geometry() plus "file" and "scene_version"); the 3-D Dummy mode's device moved
  // (SceneView::touch(), plus "scene_version"); its last position and force (SceneView::last_touch()).
  // RequestError 409 when the open file is not a scene or has not compiled yet, 501 in a studio
  // built without SANDPAPER_SHAPES. The renderer runs outside the session's mutex, under the scene's.
  nlohmann::json scene() const;
  nlohmann::json scene_touch(const SceneView::Point_m& device_m, const std::optional<SceneView::Point_m>& from_m);
  nlohmann::json scene_device() const;

  // The preview file `name` (height.png, field.png, scan.svg, preview.json, field.json, or
  // patch-<i>.png / patch-<i>-field.png for a workspace's patch) of the playing program, or nullopt if
  // there is none. Waits (up to `wait`) until the program of load `min_version` or a later one is drawn;
  // RequestError 503 if it is not drawn by then (the files there are an older load's).
  std::optional<std::filesystem::path> preview_file(const std::string& name, std::uint64_t min_version = 0,
                                                    std::chrono::milliseconds wait = std::chrono::seconds(10)) const;

  // Zoom and pan: the playing material's height field (`kind` "height") or force field at rest
  // ("field", as field.png draws it) over `window_mm` (width, height) centred on `centre_mm` (patch
  // coordinates, mm), at most kViewSide pixels on its longer side. Returns {"png": the picture's URL
  // path, "kind", "centre_mm", "window_mm" (as drawn: whole pixels), "pixel_mm", "finer_than_pixel",
  // "field_max_N" (field), "left_out", "version"}. RequestError 400 for a window that is not positive
  // and finite, larger than twice the patch or smaller than 0.01 mm, or a centre outside the patch;
  // 409 when nothing has compiled or the open file is a workspace.
  nlohmann::json render_view(const std::string& kind, const double centre_mm[2], const double window_mm[2]);
  // A picture render_view drew ("view-<n>.png"; the last kKeptViews are kept), or nullopt.
  std::optional<std::filesystem::path> view_file(const std::string& name) const;
  static constexpr int kViewSide = 512;
  static constexpr int kKeptViews = 8;

 private:
  nlohmann::json update_locked(const std::string& text);
  std::filesystem::path new_file_path(const std::string& relative) const;
  nlohmann::json parameters_locked() const;
  // The open scene's view, or why there is none (RequestError 409/501).
  std::pair<std::shared_ptr<SceneView>, std::uint64_t> scene_locked() const;
  // The preview renderer's thread: draws the newest program that compiled, off the request path, so an
  // edit is answered (and swapped in) as soon as it compiles.
  void render_loop();
  void render(const std::shared_ptr<const schema::PatchProgram>& program,
              const std::shared_ptr<const schema::WorkspaceProgram>& workspace);

  const compiler::Compiler& compiler_;
  LiveLoop& loop_;
  std::filesystem::path root_, preview_dir_;
  mutable std::mutex mutex_;
  mutable std::condition_variable rendered_;  // signalled when rendered_version_ changes
  std::condition_variable to_render_;         // signalled when version_ changes or on quit
  std::uint64_t rendered_version_ = 0;
  bool quit_ = false;
  std::thread renderer_;
  std::string file_;           // relative to root_
  FileKind kind_ = FileKind::Material;
  std::string text_;           // as edited
  std::string saved_text_;     // as on disk
  // Files opened, edited and left unsaved: their edited and on-disk texts, by relative path.
  struct Draft {
    std::string text, saved_text;
  };
  std::map<std::string, Draft> drafts_;
  // Files whose text came from a recovery copy this session, by relative path: the copy's name.
  std::map<std::string, std::string> recovered_;
  bool text_compiles_ = false;
  std::uint64_t version_ = 0;  // of the playing program (LiveLoop's load version)
  std::uint64_t text_version_ = 0;  // every change of text_ (or of the open file) raises it
  std::shared_ptr<const schema::PatchProgram> program_;
  std::atomic<std::uint64_t> views_drawn_{0};
  std::shared_ptr<const schema::WorkspaceProgram> workspace_;
  // The open scene's last good compile (null while none, or the open file is not a scene), and a
  // number that rises with each, for the page to know when to fetch the geometry again.
  std::shared_ptr<SceneView> scene_;
  std::uint64_t scene_version_ = 0;
  nlohmann::json last_compile_;
};

}  // namespace sandpaper::studio
