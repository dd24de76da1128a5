// The open scene in a studio built without the shapes room (SANDPAPER_SHAPES off): the folder's
// scene files are listed, and opening one says how to build a studio that shows it (scene_view.hpp).
#include "sandpaper/studio/scene_view.hpp"

#include "sandpaper/http/local_server.hpp"

namespace sandpaper::studio {

struct SceneView::Impl {};

bool SceneView::built() noexcept { return false; }

std::string SceneView::unbuilt_message() {
  return "this studio was built without SANDPAPER_SHAPES: scene files (.hsc) need the shapes room "
         "(cmake -DSANDPAPER_SHAPES=ON, on in the release preset)";
}

SceneView::SceneView(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
SceneView::~SceneView() = default;

SceneView::Compiled SceneView::compile(const compiler::Compiler&, const std::string&, const std::string&,
                                       const std::filesystem::path&) {
  throw http::RequestError(501, unbuilt_message());
}

nlohmann::json SceneView::geometry() const { throw http::RequestError(501, unbuilt_message()); }

nlohmann::json SceneView::touch(const Point_m&, const std::optional<Point_m>&) {
  throw http::RequestError(501, unbuilt_message());
}

nlohmann::json SceneView::last_touch() const { throw http::RequestError(501, unbuilt_message()); }

}  // namespace sandpaper::studio
