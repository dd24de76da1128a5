// catalog_index_page_scale N OUT_DIR [THUMBNAILS]: the catalog's index page for N synthetic entries,
// written as `sandpaper library catalog` writes it (OUT_DIR/index.html, the data file, assets/), without
// compiling or drawing N materials, which at 100,000 entries would take hours. Only the first
// THUMBNAILS entries with a picture (default 200: the first two pages) get a thumbnail file, a synthetic
// grating, so the screenshot shows pictures where the page asks for them.
//
// The entries follow fixed rules of their index i, so that tests/catalog/index_scale_browser_test.py
// computes every expected count on its own; change both together:
//   name        kNouns[i % 5] + "-" + i as 6 digits           ("weave-000000", "grit-000001", ...)
//   family      kFamilies[i % 7], none when i % 7 == 6
//   roughness   none when i % 11 == 0; else ((i * 7919) % 1200 + 1) / 1000
//   thumbnail   none when i % 11 == 0 and i is odd
//   describes   kAdjectives[i % 13] + " " + kTextures[(i / 13) % 17] + " surface",
//               + ", like a corduroy" when i % 9973 == 17
//   aliases     "alt-<name>" when i % 50 == 3, and "second-<name>" too when i % 500 == 3;
//               "corduroy-cloth-<i>" when i % 30011 == 29
//   deprecated  by the entry before it when i % 97 == 5
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "sandpaper/catalog/assets.hpp"
#include "sandpaper/catalog/index_page.hpp"
#include "sandpaper/catalog/render.hpp"

namespace {
namespace fs = std::filesystem;
using sandpaper::catalog::IndexRow;

const char* const kNouns[] = {"weave", "grit", "grain", "plate", "sheet"};
const char* const kFamilies[][2] = {{"textiles", "Textiles"}, {"stone", "Stone"},   {"wood", "Wood"},
                                    {"metals", "Metals"},     {"papers", "Papers"}, {"plastics", "Plastics"}};
const char* const kAdjectives[] = {"soft",   "coarse", "ribbed",  "woven",  "smooth", "gritty", "polished",
                                   "brushed", "knitted", "grainy", "waxy", "dimpled", "fibrous"};
const char* const kTextures[] = {"cotton", "linen",  "granite", "slate",  "oak",   "pine",    "steel",  "brass", "kraft",
                                 "vellum", "nylon",  "felt",    "canvas", "tweed", "leather", "basalt", "maple"};

std::string name_of(int i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s-%06d", kNouns[i % 5], i);
  return buf;
}

IndexRow row_of(int i) {
  IndexRow r;
  r.name = name_of(i);
  if (i % 7 != 6) r.family = kFamilies[i % 7][0];
  if (i % 11 != 0) {
    const int k = static_cast<int>((static_cast<long long>(i) * 7919) % 1200);
    r.roughness = (k + 1) / 1000.0;
    r.max_lateral_force_N = 0.5 * *r.roughness;
  }
  r.describes = std::string(kAdjectives[i % 13]) + " " + kTextures[(i / 13) % 17] + " surface";
  if (i % 9973 == 17) r.describes += ", like a corduroy";
  if (i % 50 == 3) r.aliases.push_back("alt-" + r.name);
  if (i % 500 == 3) r.aliases.push_back("second-" + r.name);
  if (i % 30011 == 29) r.aliases.push_back("corduroy-cloth-" + std::to_string(i));
  if (i % 97 == 5) r.deprecated_by = name_of(i - 1);
  r.licence = "CC0-1.0";
  r.page = "entries/" + r.name + ".html";
  if (!(i % 11 == 0 && i % 2 == 1)) r.thumbnail = "entries/" + r.name + "-thumb.png";
  return r;
}

// A grating of a period that varies with i, lit from the upper left as the catalog's pictures are.
sandpaper::catalog::Picture synthetic_thumbnail(int i) {
  sandpaper::catalog::Picture p;
  p.nx = p.ny = 64;
  p.shade.width = p.shade.height = 64;
  p.shade.values.resize(64 * 64);
  const double period = 4 + i % 9;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      p.shade.values[static_cast<std::size_t>(y) * 64 + x] =
          static_cast<std::uint8_t>(128 + 90 * std::sin(2 * 3.14159265358979 * (x + (i % 3) * y) / period));
  return p;
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out.flush()) throw std::runtime_error("cannot write " + file.string());
}

bool parse_count(const char* text, int& out) {
  const std::string s = text;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size() && out >= 0;
}
}  // namespace

int main(int argc, char** argv) {
  int n = 0, thumbnails = 200;
  if (argc < 3 || argc > 4 || !parse_count(argv[1], n) || (argc == 4 && !parse_count(argv[3], thumbnails))) {
    std::cerr << "usage: catalog_index_page_scale N OUT_DIR [THUMBNAILS]\n";
    return 2;
  }
  try {
    const fs::path out = argv[2];
    fs::create_directories(out / "assets");
    fs::create_directories(out / "entries");
    sandpaper::compiler::LibraryManifest manifest;
    manifest.name = "Synthetic library";
    manifest.version = "0.0.0";
    for (const auto& f : kFamilies) manifest.families.push_back({f[0], f[1], std::string("synthetic ") + f[0], false});
    std::vector<IndexRow> rows;
    rows.reserve(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) rows.push_back(row_of(i));
    for (int i = 0, drawn = 0; i < n && drawn < thumbnails; ++i)
      if (!rows[static_cast<std::size_t>(i)].thumbnail.empty()) {
        sandpaper::catalog::write_png(out / rows[static_cast<std::size_t>(i)].thumbnail, synthetic_thumbnail(i));
        ++drawn;
      }
    // As curation/catalog/src/catalog.cpp writes the index.
    fs::create_directories(out / sandpaper::catalog::kIndexPartsFolder);
    for (const auto& [relative, text] : sandpaper::catalog::index_files(manifest, rows)) write_text(out / relative, text);
    for (const auto& a : sandpaper::catalog::assets())
      write_text(out / "assets" / std::string(a.name), std::string(a.text));
  } catch (const std::exception& e) {
    std::cerr << "catalog_index_page_scale: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
