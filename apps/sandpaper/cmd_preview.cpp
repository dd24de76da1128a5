// `sandpaper preview FILE -o DIR`: the studio's preview pictures as files (docs/STUDIO.md, "Preview").
#include <iostream>

#include <fmt/format.h>

#include "cli.hpp"
#include "subsystems.hpp"
#include "sandpaper/catalog/preview.hpp"
#include "sandpaper/schema/json_text.hpp"

namespace sandpaper::cli {

int cmd_preview(const CommonOptions& o, const std::string& out_dir, int side) {
  if (out_dir.empty()) {
    std::cerr << "sandpaper preview: give the folder to write with -o DIR\n";
    return kExitUsage;
  }
  if (side < 16 || side > 4096) {
    std::cerr << "sandpaper preview: --side must be 16 to 4096 pixels\n";
    return kExitUsage;
  }
  if (std::filesystem::exists(out_dir) && !std::filesystem::is_directory(out_dir)) {
    std::cerr << "sandpaper preview: " << out_dir << " exists and is not a folder\n";
    return kExitUsage;
  }
  if (is_scene_input(o)) {
#if SANDPAPER_WITH_SHAPES
    return cmd_scene_preview(o, out_dir, side);
#else
    say_unbuilt("sandpaper preview " + o.file, kShapes);
    return kExitUsage;
#endif
  }
  if (is_workspace_input(o)) {
    std::cerr << "sandpaper preview: takes one material (.hmat, .patch or -e); a workspace's patches are previewed one "
                 "by one, or all together in `sandpaper studio`\n";
    return kExitUsage;
  }
  auto c = make_compiler(o);
  auto in = load_input(o, c, /*allow_patch=*/true);
  if (!in) return kExitBadInput;
  const auto files = catalog::write_preview(in->program, out_dir, side);
  if (o.json) {
    auto j = files.summary;
    j["folder"] = out_dir;
    std::cout << schema::json_text(j, 2) << "\n";
    return kExitOk;
  }
  const auto& s = files.summary;
  std::cout << in->program.name << " -> " << out_dir << "/\n";
  if (s.contains("pixels"))
    std::cout << fmt::format("  height.png  shaded height field, {} x {} px, {:.4g} mm per pixel, scale bar {:g} mm\n",
                             s["pixels"][0].get<int>(), s["pixels"][1].get<int>(), s["pixel_mm"].get<double>(),
                             s["scale_bar_mm"].get<double>())
              << fmt::format("  field.png   lateral force field at rest, hue = direction, brightness = |F| up to {:.4g} N\n",
                             s["field_max_N"].get<double>());
  else
    std::cout << "  (no picture: no force depends on position alone)\n";
  std::cout << "  scan.svg    lateral force " << s["scan"]["description"].get<std::string>() << ", axes in mm and N\n"
            << "  preview.json\n";
  for (const auto& why : s["left_out"]) std::cout << "  not drawn: " << why.get<std::string>() << "\n";
  if (s.contains("field_left_out"))
    for (const auto& why : s["field_left_out"]) std::cout << "  not in field.png: " << why.get<std::string>() << "\n";
  return kExitOk;
}

}  // namespace sandpaper::cli
