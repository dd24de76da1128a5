// `sandpaper library catalog -o DIR`: the library's static web catalog (curation/catalog/, docs/CATALOG.md).
#include <unistd.h>

#include <iostream>
#include <optional>

#include <CLI/CLI.hpp>

#include "cli.hpp"
#include "sandpaper/catalog/catalog.hpp"

namespace sandpaper::cli {
namespace {

struct LibraryCatalogOptions {
  std::string output;
  bool quiet = false, arrays = false;
  std::vector<std::string> changed;
  CommonOptions common;
};
LibraryCatalogOptions catalog_options;

}  // namespace

CLI::App* add_library_catalog_command(CLI::App& library) {
  auto& o = catalog_options;
  auto* sub = library.add_subcommand("catalog", "write the library's static web catalog: an index page that filters by "
                                                "family and roughness, and a page per entry with its shaded height field "
                                                "and lateral-force plot (open DIR/index.html; no server needed)");
  sub->add_option("-o,--output", o.output, "folder to write (replaced whole; an existing folder must be a catalog or empty)")
      ->required();
  sub->add_option("--device", o.common.device, "device calibration to compile for (calibration/devices/)")->capture_default_str();
  sub->add_option("--library", o.common.library_dir, "library folder, or folders front first as LAB:WORLD (default: $SANDPAPER_LIBRARY_PATH, $SANDPAPER_LIBRARY, $SANDPAPER_DATA_DIR/library, or the shipped library)");
  sub->add_option("--calibration", o.common.calibration_dir,
                  "calibration folder (default: $SANDPAPER_CALIBRATION, $SANDPAPER_DATA_DIR/calibration, or the shipped calibration)");
  sub->add_flag("--quiet", o.quiet, "no progress on stderr and no summary on stdout: only errors");
  sub->add_flag("--arrays", o.arrays, "also write each picture as Sandpaper's .shade array file (147 KB an entry: 384 x 384, one byte a pixel)");
  sub->add_option("--changed", o.changed,
                  "only these library files changed (as `library index --changed`; - reads them from stdin): "
                  "bring the index up to date from them without looking at the rest of the library")
      ->expected(1, -1);
  return sub;
}

int cmd_library_catalog(const CommonOptions& outer) {
  auto o = catalog_options;
  // `sandpaper library --library X catalog ...` works too: the group's options fill what catalog's did not.
  if (o.common.library_dir.empty()) o.common.library_dir = outer.library_dir;
  if (o.common.calibration_dir.empty()) o.common.calibration_dir = outer.calibration_dir;
  catalog::CatalogOptions co;
  co.output = o.output;
  co.arrays = o.arrays;
  if (!o.quiet) co.progress = &std::cerr;
  co.progress_is_tty = isatty(STDERR_FILENO);
  const auto roots = o.common.library_dir.empty() ? compiler::default_library_path() : compiler::split_library_path(o.common.library_dir);
  if (!o.changed.empty()) {
    if (o.common.device != "sim") {
      std::cerr << "sandpaper library catalog: --changed works on a catalog drawn for the sim device (from the library's index)\n";
      return kExitUsage;
    }
    co.changed = changed_files(o.changed);
  }
  bool folders = !roots.empty();
  for (const auto& r : roots) folders = folders && std::filesystem::is_directory(r);
  // Drawn from the indexes: one root's, or every root's of a layered path (docs/CATALOG.md).
  auto report_from_index = !folders            ? std::nullopt
                           : roots.size() == 1 ? catalog::write_catalog_from_index(roots.front(), o.common.calibration_dir, o.common.device, co)
                                               : catalog::write_catalog_from_layers(roots, o.common.calibration_dir, o.common.device, co);
  const auto report = report_from_index ? std::move(*report_from_index) : catalog::write_catalog(make_compiler(o.common), co);
  if (!report.failures.empty()) {
    for (const auto& f : report.failures) std::cerr << f.diagnostics;
    std::cerr << "sandpaper library catalog: " << report.failures.size() << " entr"
              << (report.failures.size() == 1 ? "y does" : "ies do") << " not compile:";
    for (const auto& f : report.failures) std::cerr << " " << f.name;
    std::cerr << "; nothing was written (" << o.output << " is as it was)\n";
    return kExitBadInput;
  }
  if (o.quiet) return kExitOk;
  std::cout << "catalog of " << report.entries << (report.entries == 1 ? " entry" : " entries") << " -> " << o.output << "/index.html (" << report.rendered << " drawn, "
            << report.reused << " unchanged" << (report.in_place && report.rendered > 0 ? ", updated in place" : "")
            << (report.record_unreadable ? "; the previous catalog's record (inputs.sqlite) was damaged, so every entry was drawn again" : "")
            << ")\n";
  return kExitOk;
}

}  // namespace sandpaper::cli
