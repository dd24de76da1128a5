#pragma once
// Reading a picture as heights (thesis 3.2.2 "textures from real-world data", 3.5.3): any image
// OpenImageIO reads, or Sandpaper's own .depth array file (Appendix B), reduced to one height per
// sample by the documented channel rule (docs/TEXTURES.md, "Real images"), optionally inverted and
// resampled. Shared by the heightmap statement and `sandpaper array`.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sandpaper::compiler {

// Largest height grid accepted, in samples (width * height), before and after resampling.
inline constexpr long long kMaxImagePixels = 4096LL * 4096LL;
// Multiply-adds an image's smoothing may take (both passes; a pass sums 2 ceil(3 sigma) + 1 taps per
// sample), beyond it E0304 before the blur runs: about 1.5 s on one core in a release build, 110
// times the largest shipped image's (8.9e6, library/outdoors/asphalt.hmat). A 16 x 64,524 px TIFF
// under 0.5 mm over 20 mm took 1e10: 4 s in release, over 25 s under ASan.
inline constexpr double kMaxImageSmoothingOps = 1e9;
// Resampling (`sampling`, OpenImageIO's resize) walks a window of source pixels for each sample
// (height_field_image.cpp, resample_plan). Its y window is kept on a thread's stack, and OpenImageIO
// aborts past 2^20 pixels (F39): at most kMaxResampleTaps. Its x window's weights, one set for each
// column of samples, are on the heap: at most kMaxResampleXWeights (64 MiB; a 16,000,000 x 1 px
// picture over 3 columns took 268 MiB of them, 509 MB at peak). The whole resize makes at most
// kMaxImageResampleVisits pixel visits, 5 to 20 s of CPU in a release build depending on the shape
// (resample_plan); 4096 x 4096 px to 4095 x 4095, the costliest resize that keeps the picture's
// shape, is 1.5e9 (4 s). Beyond any limit, E0402 before the resize, naming a sampling that fits.
inline constexpr long long kMaxResampleTaps = 65537;
inline constexpr long long kMaxResampleXWeights = 16777216;
inline constexpr double kMaxImageResampleVisits = 2e9;

// Multiply-adds of an image's smoothing (height_field.cpp's blur_x + blur_y) on an nx x ny grid with
// dx x dy m per sample, under a Gaussian of sigma_m m: each pass sums 2 ceil(3 sigma) + 1 taps per
// sample, none under 0.3 px. In double: a sigma of millions of px can be asked for.
double smoothing_ops(double nx, double ny, double dx, double dy, double sigma_m);

// Whether `sampling` may resample a source_nx x source_ny px picture to tx x ty samples: within
// kMaxResampleTaps and kMaxImageResampleVisits (always, when the sizes match: no resize). For
// suggestions that name a sampling, so that the sampling they name compiles.
bool resample_within_limits(int source_nx, int source_ny, int tx, int ty);

struct HeightFieldImageRequest {
  std::string path;        // file to open
  std::string shown_path;  // as the user wrote it, for messages
  std::string channel;     // a channel name; empty: the luminance rule
  bool invert = false;     // dark = high
  // Resampling to a spacing of `sampling_m` over a width_m x height_m patch (OpenImageIO resize);
  // without it, one sample per pixel.
  std::optional<double> sampling_m;
  double width_m = 0, height_m = 0;
  // The smoothing the heights will get (m), or none. Not applied here: a sampling that E0402
  // suggests must also keep it within kMaxImageSmoothingOps.
  std::optional<double> smoothing_m;
};

// Heights in the image's own unit: integer pixels 0..1 (OpenImageIO's normalisation), float pixels
// as stored, .depth items value / 255. Row-major, row 0 = the picture's top edge.
struct HeightFieldImage {
  int nx = 0, ny = 0;
  std::vector<float> values;
  float lo = 0, hi = 0;        // range of the source's heights (after inversion, before resampling)
  int source_nx = 0, source_ny = 0;
  std::string description;     // "512 x 512 px, 1 channel Y (uint8), ...", for provenance
};

// A picture that cannot be used: code (E0401-E0406, schema/LANGUAGE.md), what, how to fix it.
struct HeightFieldImageError {
  std::string code, message, suggestion;
};

// Returns nullopt and fills `error` for a file that is unreadable (E0401), of no or too many
// samples (E0402), flat or non-finite (E0403), without the named channel (E0404), a .depth of the
// wrong size (E0405) or a .shade picture (E0406).
std::optional<HeightFieldImage> load_height_field_image(const HeightFieldImageRequest& request, HeightFieldImageError& error);

// The picture's size, {width, height} in px (items for a .depth), from its header alone; nullopt
// when it cannot be opened (load_height_field_image then says why, with the same checks).
std::optional<std::pair<int, int>> height_field_image_size(const std::string& path);

}  // namespace sandpaper::compiler
