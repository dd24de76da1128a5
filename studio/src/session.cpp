#include "sandpaper/studio/session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <sys/resource.h>
#include <unistd.h>

#include "sandpaper/catalog/preview.hpp"
#include "sandpaper/compiler/brought_in.hpp"
#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/workspace.hpp"
#include "sandpaper/lsp/features.hpp"
#include "sandpaper/lsp/text_positions.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "sandpaper/schema/workspace_json.hpp"
#include "sandpaper/http/request_guard.hpp"

namespace sandpaper::studio {
namespace fs = std::filesystem;

namespace {

// The preview pane's pictures: big enough for a 1080p screen's half, small enough to render on every
// keystroke's compile in a few tens of milliseconds.
constexpr int kPreviewSide = 384;
constexpr int kPatchPictureSide = 160;
constexpr int kFieldArrows = 24;

// A length in a message: 4 significant figures.
std::string fmt_mm(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

nlohmann::json parameter_json(const compiler::Parameter& p) {
  return {{"name", p.name},   {"label", p.label}, {"layer", p.layer}, {"value", p.value}, {"unit", p.unit},
          {"si", p.si},       {"min", p.min},     {"max", p.max},     {"step", p.step},   {"line", p.line},
          {"column", p.column}, {"length", p.length}};
}

// The compiler's limit on a source file (schema/input_limits.hpp), as a person reads it: "4 MiB".
std::string source_limit_text() { return std::to_string(schema::limits::kMaxSourceBytes >> 20) + " MiB"; }

// A diagnostic from another file (a library entry the text builds on) keeps its own place ("location",
// "line", "column": in that file) and says where it came into the open text: "file" (its file),
// "brought_in" ({line, column, length}: the `like` or the patch) and "entry" (the library entry).
void mark_brought_in(nlohmann::json& diagnostics, const compiler::Diagnostics& ds, const std::string& name,
                     const std::string& text, const compiler::Library& library) {
  const auto file = std::make_shared<const compiler::SourceFile>(name, text);
  const auto& all = ds.all();
  for (std::size_t i = 0; i < all.size() && i < diagnostics.size(); ++i) {
    const auto b = compiler::brought_in(all[i], file, library);
    if (!b) continue;
    auto& j = diagnostics[i];
    j["file"] = all[i].location.file->name;
    j["brought_in"] = {{"line", b->at.line}, {"column", b->at.column}, {"length", b->at.length}};
    j["entry"] = b->entry.empty() ? nlohmann::json(nullptr) : nlohmann::json(b->entry);
  }
}

std::string read_text(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw RequestError(404, "no file " + path.filename().string() + " in the studio's folder");
  if (fs::file_size(path, ec) > schema::limits::kMaxSourceBytes)
    throw RequestError(413, path.filename().string() + " is larger than " + source_limit_text() +
                                ", the most the compiler reads; the studio edits material and workspace files");
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

Session::Session(const compiler::Compiler& compiler, LiveLoop& loop, fs::path root, fs::path preview_dir)
    : compiler_(compiler), loop_(loop), root_(std::move(root)), preview_dir_(std::move(preview_dir)) {
  fs::create_directories(preview_dir_);
  renderer_ = std::thread([this] { render_loop(); });
}

Session::~Session() {
  {
    std::lock_guard lock(mutex_);
    quit_ = true;
  }
  to_render_.notify_all();
  renderer_.join();
}

nlohmann::json Session::files() const {
  std::vector<std::string> names, not_utf8;
  std::error_code ec;
  fs::recursive_directory_iterator it(root_, fs::directory_options::skip_permission_denied, ec), end;
  for (; !ec && it != end && names.size() + not_utf8.size() < 2000; it.increment(ec)) {
    if (it.depth() > 8) {
      it.disable_recursion_pending();
      continue;
    }
    const auto name = it->path().filename().string();
    if (it->is_directory(ec) && (name.starts_with(".") || name == "node_modules" || name == "build")) {
      it.disable_recursion_pending();
      continue;
    }
    if (file_kind(it->path()) && it->is_regular_file(ec)) {
      std::string relative = fs::relative(it->path(), root_).string();
      std::size_t bad = 0;
      (schema::is_valid_utf8(relative, bad) ? names : not_utf8).push_back(std::move(relative));
    }
  }
  std::sort(names.begin(), names.end());
  std::sort(not_utf8.begin(), not_utf8.end());
  // The page names a file in JSON, which holds only UTF-8: such a name could be shown (with U+FFFD)
  // but never opened, so it is listed apart, with what to do (as the library's E0614 does).
  auto unlisted = nlohmann::json::array();
  for (const auto& n : not_utf8)
    unlisted.push_back({{"file", schema::replace_invalid_utf8(n)},
                        {"why", "its name is not UTF-8: rename the file in UTF-8 to open it here"}});
  auto unsaved = nlohmann::json::array();
  {
    std::lock_guard lock(mutex_);
    for (const auto& [file, draft] : drafts_) unsaved.push_back(file);
    if (!file_.empty() && text_ != saved_text_ && !drafts_.contains(file_)) unsaved.push_back(file_);
  }
  return {{"files", names}, {"not_listed", std::move(unlisted)}, {"unsaved", std::move(unsaved)}};
}

nlohmann::json Session::open(const std::string& relative) {
  fs::path full;
  try {
    full = http::confined_path(root_, relative);
  } catch (const http::OutsideFolder& e) {
    throw RequestError(403, e.what());
  }
  const auto kind = file_kind(full);
  if (!kind) throw RequestError(400, "'" + relative + "' is not " + kinds_text() + " file");
  // Refused before the open file is left: a studio that cannot show the scene keeps what it had.
  if (*kind == FileKind::Scene && !SceneView::built()) throw RequestError(501, SceneView::unbuilt_message());
  const std::string name = fs::relative(full, root_).string();
  std::lock_guard lock(mutex_);
  std::string text, saved;
  const auto draft = drafts_.find(name);
  const bool reopened = name == file_ && text_ != saved_text_;
  const bool restored = reopened || draft != drafts_.end();
  if (reopened) {
    text = text_;
    saved = saved_text_;
  } else if (restored) {
    text = draft->second.text;
    saved = draft->second.saved_text;
  } else {
    // Read before the open file is left, so that a refusal (404, 413) changes nothing.
    text = saved = read_text(full);
    const fs::path copy = recovery_path(full);
    std::error_code ec;
    if (fs::is_regular_file(copy, ec) && fs::file_size(copy, ec) <= schema::limits::kMaxSourceBytes) {
      std::string kept = read_text(copy);
      if (kept != saved) {
        text = std::move(kept);
        recovered_[name] = fs::relative(copy, root_).string();
      } else {
        fs::remove(copy, ec);  // nothing in it that the file does not hold
      }
    }
  }
  if (!file_.empty() && file_ != name && text_ != saved_text_) drafts_[file_] = {text_, saved_text_};
  if (draft != drafts_.end()) drafts_.erase(draft);
  file_ = name;
  kind_ = *kind;
  scene_.reset();  // another file's scene is not this one's, even while this one does not compile
  saved_text_ = std::move(saved);
  nlohmann::json j = update_locked(text);
  j["file"] = file_;
  j["restored_unsaved"] = restored;
  if (const auto r = recovered_.find(file_); r != recovered_.end() && text_ != saved_text_) j["recovered"] = r->second;
  return j;
}

nlohmann::json Session::current() const {
  std::lock_guard lock(mutex_);
  nlohmann::json recovered;
  if (const auto r = recovered_.find(file_); r != recovered_.end() && text_ != saved_text_)
    recovered = {{"copy", r->second}, {"saved_text", saved_text_}};
  return {{"file", file_},
          {"recovered", recovered},
          {"kind", kind_name(kind_)},
          {"scene_version", scene_version_},
          {"text", text_},
          {"text_version", text_version_},
          {"saved", text_ == saved_text_},
          {"version", version_},
          {"compiles", text_compiles_},
          {"compile", last_compile_},
          {"parameters", parameters_locked()}};
}

nlohmann::json Session::document_state() const {
  std::lock_guard lock(mutex_);
  return {{"file", file_},
          {"text_version", text_version_},
          {"saved", text_ == saved_text_},
          {"compiles", text_compiles_},
          {"version", version_},
          {"kind", kind_name(kind_)},
          {"scene_version", scene_version_}};
}

nlohmann::json Session::compile_only(const std::string& text) const {
  if (text.size() > schema::limits::kMaxSourceBytes) throw RequestError(413, "a material is at most " + source_limit_text() + " of text");
  std::lock_guard lock(mutex_);
  return compiler::compile_json(compiler_.compile_text(text, file_.empty() ? "<studio>" : file_), std::nullopt);
}

nlohmann::json Session::parameters_locked() const {
  auto arr = nlohmann::json::array();
  if (kind_ == FileKind::Scene) return arr;  // a scene's numbers have no sliders (yet)
  const auto params = kind_ == FileKind::Workspace ? compiler::workspace_parameters(text_)
                                    : compiler::material_parameters(text_, compiler_.calibration(), loop_.limits().max_force_N);
  for (const auto& p : params) arr.push_back(parameter_json(p));
  return arr;
}

nlohmann::json Session::update(const std::string& text) {
  if (text.size() > schema::limits::kMaxSourceBytes) throw RequestError(413, "a material is at most " + source_limit_text() + " of text");
  nlohmann::json j;
  {
    std::lock_guard lock(mutex_);
    j = update_locked(text);
  }
  return j;
}

nlohmann::json Session::update_locked(const std::string& text) {
  text_ = text;
  ++text_version_;
  nlohmann::json j;
  if (kind_ == FileKind::Scene) {
    // Nothing goes to the loop: the 2-axis joystick cannot feel a scene, and keeps what it plays.
    auto c = SceneView::compile(compiler_, text, file_, (root_ / file_).parent_path());
    j = std::move(c.answer);
    mark_brought_in(j["diagnostics"], c.diagnostics, file_, text, compiler_.library());
    if (c.view) {
      scene_ = std::move(c.view);
      ++scene_version_;
    }
    j["scene_version"] = scene_version_;
  } else if (kind_ == FileKind::Workspace) {
    const auto base = (root_ / file_).parent_path();
    auto r = compiler::compile_workspace_text(compiler_, text, file_, base);
    j = {{"ok", r.ok()}, {"diagnostics", compiler::diagnostics_json(r.diagnostics)}};
    mark_brought_in(j["diagnostics"], r.diagnostics, file_, text, compiler_.library());
    if (r.ok()) {
      auto ws = std::make_shared<const schema::WorkspaceProgram>(std::move(*r.program));
      j["workspace"] = schema::to_json(*ws);
      version_ = loop_.load_workspace_nonrt(ws);
      workspace_ = std::move(ws);
      program_.reset();
    }
  } else {
    auto r = compiler_.compile_text(text, file_);
    if (r.ok()) {
      // Into the loop first: the hand feels the edit before the page's answer is built.
      auto prog = std::make_shared<const schema::PatchProgram>(std::move(*r.program));
      version_ = loop_.load_nonrt(prog, prog->roughness);
      j = compiler::compile_json(*prog, r.diagnostics, std::nullopt);
      program_ = std::move(prog);
      workspace_.reset();
    } else {
      j = compiler::compile_json(r, std::nullopt);
    }
    mark_brought_in(j["diagnostics"], r.diagnostics, file_, text, compiler_.library());
  }
  text_compiles_ = j["ok"].get<bool>();
  if (text_compiles_ && kind_ != FileKind::Scene) to_render_.notify_all();
  last_compile_ = j;
  j["parameters"] = parameters_locked();
  j["version"] = version_;
  j["playing_is_current"] = text_compiles_ && kind_ != FileKind::Scene;
  j["saved"] = text_ == saved_text_;
  j["text_version"] = text_version_;
  return j;
}

nlohmann::json Session::set_parameter(const std::string& name, double value, const std::string& unit) {
  nlohmann::json j;
  {
  std::lock_guard lock(mutex_);
  if (kind_ == FileKind::Scene) throw RequestError(400, "a scene's numbers have no parameters to set: edit its text");
  const auto params = kind_ == FileKind::Workspace ? compiler::workspace_parameters(text_)
                                    : compiler::material_parameters(text_, compiler_.calibration(), loop_.limits().max_force_N);
  std::string edited;
  try {
    edited = compiler::set_parameter(text_, params, name, value, unit);
  } catch (const compiler::ParameterError& e) {
    throw RequestError(400, e.what());
  }
  j = update_locked(edited);
  j["text"] = text_;
  }
  return j;
}

nlohmann::json Session::save() {
  std::lock_guard lock(mutex_);
  if (file_.empty()) throw RequestError(409, "no file is open");
  fs::path full;
  try {
    full = http::confined_path(root_, file_);
  } catch (const http::OutsideFolder& e) {
    throw RequestError(403, e.what());
  }
  try {
    schema::write_file_atomically(full, text_);
  } catch (const std::exception& e) {
    throw RequestError(500, std::string("could not save: ") + e.what());
  }
  saved_text_ = text_;
  // The recovered text is in the file now.
  if (recovered_.erase(file_)) {
    std::error_code ec;
    fs::remove(recovery_path(full), ec);
  }
  return {{"saved", true}, {"file", file_}, {"bytes", text_.size()}};
}

fs::path Session::recovery_path(const fs::path& file) {
  return file.parent_path() / ("." + file.filename().string() + ".recovered");
}

std::vector<Session::Unsaved> Session::keep_unsaved() {
  std::lock_guard lock(mutex_);
  std::map<std::string, std::string> unsaved;  // by file: the edited text
  for (const auto& [file, draft] : drafts_) unsaved[file] = draft.text;
  if (!file_.empty() && text_ != saved_text_) unsaved[file_] = text_;
  std::vector<Unsaved> kept;
  for (const auto& [file, text] : unsaved) {
    Unsaved u{file, {}, {}, text};
    try {
      const fs::path copy = recovery_path(http::confined_path(root_, file));
      schema::write_file_atomically(copy, text);
      u.copy = fs::relative(copy, root_).string();
    } catch (const std::exception& e) {
      u.error = e.what();
    }
    kept.push_back(std::move(u));
  }
  // A copy offered this session whose text was since saved or undone would offer it again.
  for (const auto& [file, copy] : recovered_)
    if (!unsaved.contains(file)) {
      std::error_code ec;
      fs::remove(root_ / copy, ec);
    }
  return kept;
}

fs::path Session::new_file_path(const std::string& relative) const {
  fs::path full;
  try {
    full = http::confined_path(root_, relative);
  } catch (const http::OutsideFolder& e) {
    throw RequestError(403, e.what());
  }
  const auto kind = file_kind(full);
  if (!kind) throw RequestError(400, "'" + relative + "': a material is a .hmat file, a workspace a .hws file, a scene a .hsc file");
  if (*kind == FileKind::Scene && !SceneView::built()) throw RequestError(501, SceneView::unbuilt_message());
  std::error_code ec;
  if (!fs::is_directory(full.parent_path(), ec))
    throw RequestError(404, "no folder " + fs::relative(full.parent_path(), root_).string() + " in the studio's folder");
  if (fs::exists(full, ec)) throw RequestError(409, "'" + relative + "' exists: open it, or choose another name");
  return full;
}

nlohmann::json Session::create(const std::string& relative) {
  fs::path full;
  {
    std::lock_guard lock(mutex_);
    full = new_file_path(relative);
  }
  const std::string stem = full.stem().string();
  // A start that compiles and plays: the text names its material after the file, as the library does.
  const auto kind = file_kind(full);
  const std::string text =
      kind == FileKind::Workspace
          ? "workspace \"" + stem + "\" {\n  size 228.6 mm x 228.6 mm\n}\n"
      : kind == FileKind::Scene
          ? "scene \"" + stem + "\" {\n  # a ball on a floor: left-drag on it in the studio's 3-D view to feel it\n"
                                "  object \"ball\" sphere radius 40 mm at 0 mm, 40 mm, 0 mm {\n    material \"roughness 0.5\"\n  }\n"
                                "  object \"floor\" plane 240 mm x 240 mm at 0 mm, 0 mm, 0 mm {\n    stiffness 1000 N/m\n  }\n}\n"
          : "material \"" + stem + "\" {\n  # felt on the library's reference texture until a texture is given\n"
                                   "  roughness 0.5\n}\n";
  try {
    schema::write_file_atomically(full, text);
  } catch (const std::exception& e) {
    throw RequestError(500, std::string("could not create the file: ") + e.what());
  }
  nlohmann::json j = open(fs::relative(full, root_).string());
  j["created"] = true;
  return j;
}

nlohmann::json Session::save_as(const std::string& relative) {
  std::lock_guard lock(mutex_);
  if (file_.empty()) throw RequestError(409, "no file is open");
  const fs::path full = new_file_path(relative);
  if (file_kind(full) != kind_)
    throw RequestError(400, std::string("the open file is a ") + kind_name(kind_) + ": save it as a " + kind_extension(kind_) +
                                " file");
  try {
    schema::write_file_atomically(full, text_);
  } catch (const std::exception& e) {
    throw RequestError(500, std::string("could not save: ") + e.what());
  }
  file_ = fs::relative(full, root_).string();
  saved_text_ = text_;
  ++text_version_;  // the same text, under another name: every page follows
  return {{"saved", true}, {"file", file_}, {"bytes", text_.size()}, {"text_version", text_version_}};
}

nlohmann::json Session::language(const std::string& feature, int line, int character) const {
  if (feature != "completion" && feature != "hover" && feature != "definition")
    throw RequestError(400, "\"feature\" is one of completion, hover, definition");
  std::lock_guard lock(mutex_);
  const long lines = std::count(text_.begin(), text_.end(), '\n') + 1;
  if (line < 0 || line >= lines || character < 0) throw RequestError(400, "the position is outside the text");
  // The language server reads materials and workspaces; a scene's text it would misread.
  if (kind_ == FileKind::Scene) return feature == "completion" ? nlohmann::json::array() : nlohmann::json(nullptr);
  // The document as the language server holds one: named by its absolute path, so that relative
  // image paths resolve against its folder, as they do when it plays.
  lsp::Document d;
  d.name = (root_ / (file_.empty() ? "untitled.hmat" : file_)).string();
  d.uri = lsp::uri_of_path(d.name);
  d.workspace = kind_ == FileKind::Workspace;
  if (kind_ == FileKind::Material) d.compiled = compiler_.compile_text(text_, d.name);
  d.source = std::make_shared<const compiler::SourceFile>(d.name, text_);
  const nlohmann::json position = {{"line", line}, {"character", character}};
  if (feature == "completion") return lsp::completion(d, position, compiler_);
  if (feature == "hover") return lsp::hover(d, position, compiler_);
  return lsp::definition(d, position, compiler_);
}

nlohmann::json Session::workspace() const {
  std::lock_guard lock(mutex_);
  if (kind_ != FileKind::Workspace)
    throw RequestError(409, std::string("the open file is a ") + kind_name(kind_) + ", not a workspace");
  nlohmann::json j{{"file", file_}, {"version", version_}, {"patches", nlohmann::json::array()}};
  if (!workspace_) return j;
  j["name"] = workspace_->name;
  j["size_mm"] = {workspace_->size_m[0] * 1e3, workspace_->size_m[1] * 1e3};
  for (std::size_t i = 0; i < workspace_->patches.size(); ++i) {
    const auto& p = workspace_->patches[i];
    j["patches"].push_back({{"index", i},
                            {"source", p.source},
                            {"name", p.program->name},
                            {"centre_mm", {p.centre_m[0] * 1e3, p.centre_m[1] * 1e3}},
                            {"size_mm", {p.size_m[0] * 1e3, p.size_m[1] * 1e3}},
                            {"compiled_max_lateral_force_N", p.program->max_lateral_force_N},
                            {"compiled_roughness", p.program->roughness}});
  }
  return j;
}

nlohmann::json Session::place_patch(int index, double x_mm, double y_mm, double width_mm, double height_mm) {
  nlohmann::json j;
  {
  std::lock_guard lock(mutex_);
  if (kind_ != FileKind::Workspace)
    throw RequestError(409, std::string("the open file is a ") + kind_name(kind_) + ", not a workspace");
  std::string edited;
  try {
    edited = compiler::place_workspace_patch(text_, index, x_mm, y_mm, width_mm, height_mm);
  } catch (const compiler::ParameterError& e) {
    throw RequestError(400, e.what());
  }
  j = update_locked(edited);
  j["text"] = text_;
  }
  return j;
}

void Session::render_loop() {
  // Below the request threads: an edit's compile and swap come before its picture.
  ::setpriority(PRIO_PROCESS, static_cast<id_t>(::gettid()), 10);
  std::unique_lock lock(mutex_);
  for (;;) {
    to_render_.wait(lock, [this] { return quit_ || version_ != rendered_version_; });
    if (quit_) return;
    const auto program = program_;
    const auto workspace = workspace_;
    const std::uint64_t version = version_;
    lock.unlock();
    try {
      render(program, workspace);
    } catch (const std::exception&) {
      // A picture that cannot be drawn leaves the pane without it; the material still plays.
    }
    lock.lock();
    rendered_version_ = version;
    rendered_.notify_all();
  }
}

void Session::render(const std::shared_ptr<const schema::PatchProgram>& program,
                     const std::shared_ptr<const schema::WorkspaceProgram>& workspace) {
  const fs::path dir = preview_dir_ / "current";
  fs::create_directories(dir);
  std::vector<fs::path> written;
  if (program) {
    written = catalog::write_preview(*program, dir, kPreviewSide, kFieldArrows).written;
  } else if (workspace) {
    for (std::size_t i = 0; i < workspace->patches.size(); ++i) {
      const auto& prog = *workspace->patches[i].program;
      const auto picture = catalog::render_picture(prog, kPatchPictureSide);
      if (picture.empty()) continue;
      catalog::write_image_png(dir / ("patch-" + std::to_string(i) + ".png"), catalog::grey_image(picture));
      double max_f = 0;
      catalog::write_image_png(dir / ("patch-" + std::to_string(i) + "-field.png"),
                               catalog::render_force_field(prog, picture, max_f));
      written.push_back(dir / ("patch-" + std::to_string(i) + ".png"));
      written.push_back(dir / ("patch-" + std::to_string(i) + "-field.png"));
    }
  }
  // What the previous program had and this one has not (a workspace's patches after a material) goes;
  // files written again were replaced by rename, so a page reading them never sees one half-written.
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (std::find(written.begin(), written.end(), e.path()) == written.end()) fs::remove(e.path(), ec);
}

nlohmann::json Session::render_view(const std::string& kind, const double centre_mm[2], const double window_mm[2]) {
  if (kind != "height" && kind != "field") throw RequestError(400, "?kind= is \"height\" or \"field\"");
  std::shared_ptr<const schema::PatchProgram> program;
  std::uint64_t version = 0;
  {
    std::lock_guard lock(mutex_);
    if (kind_ == FileKind::Workspace) throw RequestError(409, "the open file is a workspace: its patches have pictures of their own");
    if (kind_ == FileKind::Scene) throw RequestError(409, "the open file is a scene: the 3-D view shows it (GET /api/scene)");
    program = program_;
    version = version_;
  }
  if (!program) throw RequestError(409, "nothing has compiled yet: there is no picture to zoom");
  const double pw = program->size_m[0] * 1e3, ph = program->size_m[1] * 1e3;
  for (int a = 0; a < 2; ++a) {
    const double side = a == 0 ? pw : ph;
    if (!std::isfinite(window_mm[a]) || window_mm[a] < 0.01 || window_mm[a] > 2 * side)
      throw RequestError(400, std::string(a == 0 ? "w_mm" : "h_mm") + " must be from 0.01 mm to twice the patch's " +
                                  (a == 0 ? "width" : "height") + " (" + fmt_mm(2 * side) + " mm)");
    if (!std::isfinite(centre_mm[a]) || std::abs(centre_mm[a]) > 0.5 * side)
      throw RequestError(400, std::string(a == 0 ? "x_mm" : "y_mm") + " must lie on the patch (within " +
                                  fmt_mm(0.5 * side) + " mm of its centre)");
  }
  const double centre_m[2] = {centre_mm[0] * 1e-3, centre_mm[1] * 1e-3};
  const double window_m[2] = {window_mm[0] * 1e-3, window_mm[1] * 1e-3};
  nlohmann::json j{{"kind", kind}, {"version", version}};
  catalog::Image image;
  catalog::Picture picture;
  if (kind == "height") {
    picture = catalog::render_picture_view(*program, centre_m, window_m, kViewSide);
    if (!picture.empty()) image = catalog::grey_image(picture);
  } else {
    // The window and pixels alone: the force field draws what a slow hand meets at each place,
    // whether or not a surface shows it.
    picture = catalog::picture_frame(centre_m, window_m, kViewSide);
    picture.finer_than_pixel = catalog::finest_detail_m(*program) < picture.pixel_m;
    double max_N = 0;
    image = catalog::render_force_field(*program, picture, max_N);
    catalog::position_only(*program, picture.left_out);
    j["field_max_N"] = max_N;
    if (!(max_N > 0)) image = {};
  }
  j["left_out"] = picture.left_out;
  if (image.nx == 0) {
    j["png"] = nullptr;
    return j;
  }
  const std::uint64_t n = ++views_drawn_;
  const fs::path dir = preview_dir_ / "views";
  fs::create_directories(dir);
  const std::string name = "view-" + std::to_string(n) + ".png";
  catalog::write_image_png(dir / name, image);
  std::error_code ec;
  if (n > static_cast<std::uint64_t>(kKeptViews)) fs::remove(dir / ("view-" + std::to_string(n - kKeptViews) + ".png"), ec);
  j["png"] = "/api/view/" + name;
  j["centre_mm"] = {centre_mm[0], centre_mm[1]};
  j["window_mm"] = {picture.window_m[0] * 1e3, picture.window_m[1] * 1e3};
  j["pixel_mm"] = picture.pixel_m * 1e3;
  j["finer_than_pixel"] = picture.finer_than_pixel;
  return j;
}

std::optional<fs::path> Session::view_file(const std::string& name) const {
  static const std::regex view(R"(view-\d{1,19}\.png)");
  if (!std::regex_match(name, view)) return std::nullopt;
  const fs::path p = preview_dir_ / "views" / name;
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) return std::nullopt;
  return p;
}

std::optional<fs::path> Session::preview_file(const std::string& name, std::uint64_t min_version,
                                              std::chrono::milliseconds wait) const {
  // Names are checked against a fixed pattern: nothing from the request reaches the file system as a path.
  const bool fixed = name == "height.png" || name == "field.png" || name == "scan.svg" || name == "preview.json" ||
                     name == "field.json";
  static const std::regex patch_picture(R"(patch-\d{1,5}(-field)?\.png)");
  const bool patch = std::regex_match(name, patch_picture);
  if (!fixed && !patch) return std::nullopt;
  std::unique_lock lock(mutex_);
  const auto drawn = [&] { return rendered_version_ >= std::min(min_version, version_); };
  // An older load's picture under a newer load's name would be shown as this one's (a loaded machine
  // draws a photograph for longer than the wait): the page is told to ask again instead.
  if (!rendered_.wait_for(lock, wait, drawn))
    throw RequestError(503, "the preview of load " + std::to_string(std::min(min_version, version_)) +
                                " is still being drawn (load " + std::to_string(rendered_version_) +
                                " is drawn): ask again");
  const fs::path p = preview_dir_ / "current" / name;
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) return std::nullopt;
  return p;
}

std::pair<std::shared_ptr<SceneView>, std::uint64_t> Session::scene_locked() const {
  if (!SceneView::built()) throw RequestError(501, SceneView::unbuilt_message());
  if (kind_ != FileKind::Scene) throw RequestError(409, std::string("the open file is a ") + kind_name(kind_) + ", not a scene");
  if (!scene_) throw RequestError(409, "the scene has not compiled yet: there is nothing to draw or touch");
  return {scene_, scene_version_};
}

nlohmann::json Session::scene() const {
  std::pair<std::shared_ptr<SceneView>, std::uint64_t> s;
  std::string file;
  {
    std::lock_guard lock(mutex_);
    s = scene_locked();
    file = file_;
  }
  // Built outside the session's lock: a large mesh's arrays must not hold up the editor's compiles.
  nlohmann::json j = s.first->geometry();
  j["file"] = file;
  j["scene_version"] = s.second;
  return j;
}

nlohmann::json Session::scene_touch(const SceneView::Point_m& device_m, const std::optional<SceneView::Point_m>& from_m) {
  std::pair<std::shared_ptr<SceneView>, std::uint64_t> s;
  {
    std::lock_guard lock(mutex_);
    s = scene_locked();
  }
  nlohmann::json j = s.first->touch(device_m, from_m);
  j["scene_version"] = s.second;
  return j;
}

nlohmann::json Session::scene_device() const {
  std::pair<std::shared_ptr<SceneView>, std::uint64_t> s;
  {
    std::lock_guard lock(mutex_);
    s = scene_locked();
  }
  nlohmann::json j = s.first->last_touch();
  j["scene_version"] = s.second;
  return j;
}

}  // namespace sandpaper::studio
