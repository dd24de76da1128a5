// Hostile input to the compiler (issue 16): each case here once crashed, hung, exhausted memory or
// compiled something the runtime could not play. Limits: schema/input_limits.hpp, docs/RELIABILITY.md.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "sandpaper/compiler/compile_json.hpp"
#include "sandpaper/compiler/compiler.hpp"
#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/schema/input_limits.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace sandpaper {
namespace {

using compiler::Severity;

void write(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// Peak resident memory of this process so far, in bytes.
std::uint64_t peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<std::uint64_t>(u.ru_maxrss) * 1024;
}

// A `like` chain 700 entries deep used to recurse until the stack overflowed (segfault).
TEST(HostileInput, ADeepLikeChainIsRefusedWithTheChainNamed) {
  const fs::path lib = test::temp_dir("deep-like");
  fs::create_directories(lib / "chain");
  constexpr int kDepth = 700;
  for (int i = 0; i < kDepth; ++i) {
    const std::string body = i + 1 < kDepth ? "  like m" + std::to_string(i + 1) + "\n" : "  grating period 2 mm amplitude 1 N\n";
    write(lib / "chain" / ("m" + std::to_string(i) + ".hmat"), "material \"m" + std::to_string(i) + "\" {\n" + body + "}\n");
  }
  compiler::CompileOptions options;
  options.library_dir = lib;
  const compiler::Compiler c(options);
  const auto r = c.compile_text("like m0", "<deep>");
  ASSERT_FALSE(r.ok());
  // The error is at the 64th link; each level above reports its entry as broken (E0306).
  bool found = false;
  for (const auto& d : r.diagnostics.all())
    for (const auto& n : d.notes)
      found = found || (n.message.find("chain deeper than 64") != std::string::npos &&
                        n.message.find("m0 -> m1 -> m2 -> ...") != std::string::npos);
  EXPECT_TRUE(found) << compiler::format_diagnostics(r.diagnostics).substr(0, 2000);
  // A chain within the limit still compiles.
  EXPECT_TRUE(c.compile_text("like m660", "<shallow>").ok());
}

// 40,000 stray characters on one line used to give 40,000 errors, each echoing the 40 KB line
// (2.4 GB of text): now one error for the run, and any echoed line is clipped around its caret.
TEST(HostileInput, ALongLineOfStrayCharactersGivesOneShortDiagnostic) {
  const std::string line(40000, '@');
  const auto r = test::shipped_compiler().compile_text("material \"m\" {\n" + line + "\n}\n", "<stray>");
  ASSERT_FALSE(r.ok());
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0102"});
  const std::string text = compiler::format_diagnostics(r.diagnostics);
  EXPECT_LT(text.size(), 1000u) << text.substr(0, 400);
  EXPECT_NE(text.find("unexpected characters '@@@@@@@@@@@@@@@@...'"), std::string::npos) << text;
  EXPECT_NE(text.find("..."), std::string::npos);
}

// Many distinct errors: at most kMaxErrorsPerFile are kept, then one E0009 counts the rest.
TEST(HostileInput, ErrorsPerFileAreCappedWithACount) {
  std::string text = "material \"m\" {\n";
  for (int i = 0; i < 5000; ++i) text += "  grating period 2 mn\n";  // unknown unit, one error each
  text += "}\n";
  const auto r = test::shipped_compiler().compile_text(text, "<many>");
  const auto codes = test::codes(r);
  ASSERT_EQ(codes.size(), schema::limits::kMaxErrorsPerFile + 1);
  EXPECT_EQ(codes.back(), "E0009");
  EXPECT_NE(r.diagnostics.all().back().message.find("4950 more not shown"), std::string::npos)
      << r.diagnostics.all().back().message;
}

// An echoed line is clipped around the caret, wherever the caret is, and the caret stays under
// the text it points at.
TEST(HostileInput, EchoedLinesAreClippedAroundTheCaret) {
  const std::string pad(30000, ' ');
  const auto r = test::shipped_compiler().compile_text("material \"m\" {\n" + pad + "grating period 2 mn" + pad + "\n}\n", "<wide>");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0204"});
  const std::string text = compiler::format_diagnostics(r.diagnostics);
  EXPECT_LT(text.size(), 800u);
  // The caret line's '^' sits under the 'm' of "mn" in the echoed line.
  std::vector<std::string> lines;
  for (std::size_t b = 0, e; b < text.size(); b = e + 1) {
    e = text.find('\n', b);
    if (e == std::string::npos) e = text.size();
    lines.push_back(text.substr(b, e - b));
  }
  std::size_t echoed = 0;
  while (echoed < lines.size() && lines[echoed].find(" | ...") == std::string::npos) ++echoed;
  ASSERT_LT(echoed + 1, lines.size()) << text;
  EXPECT_EQ(lines[echoed].find("mn"), lines[echoed + 1].find('^')) << lines[echoed] << "\n" << lines[echoed + 1];
}

TEST(HostileInput, AnOversizedSourceIsRefusedBeforeLexing) {
  const std::string big(schema::limits::kMaxSourceBytes + 1, '#');
  const auto before = peak_rss_bytes();
  const auto r = test::shipped_compiler().compile_text(big, "<big>");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0105"});
  EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{64} << 20);
}

// A byte that is not UTF-8 used to pass into `describes` and make every --json output throw
// nlohmann's type_error 316. Now: an error at its line and column, and JSON that can be written.
TEST(HostileInput, NonUtf8SourceIsAnErrorAtItsPlaceAndJsonStillWrites) {
  const std::string text = "material \"m\" {\n  describes \"caf\xE9 au lait\"\n  grating period 2 mm amplitude 1 N\n}\n";
  const auto r = test::shipped_compiler().compile_text(text, "<latin1>");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0104"});
  const auto& d = r.diagnostics.all().front();
  EXPECT_EQ(d.location.line, 2);
  EXPECT_EQ(d.location.column, 17);
  EXPECT_NE(d.message.find("0xE9"), std::string::npos);
  EXPECT_NO_THROW((void)compiler::compile_json(r, std::nullopt).dump());
  // Valid UTF-8 outside ASCII is fine in strings ...
  EXPECT_TRUE(test::shipped_compiler()
                  .compile_text("material \"m\" {\n  describes \"caf\xC3\xA9\"\n  grating period 2 mm amplitude 1 N\n}\n", "<utf8>")
                  .ok());
  // ... and an overlong encoding, a surrogate or a truncated sequence is not.
  for (const std::string bad : {"\xC0\xAF", "\xED\xA0\x80", "\xE2\x82"}) {
    const auto b = test::shipped_compiler().compile_text("material \"m\" {\n  describes \"" + bad + "\"\n}\n", "<bad>");
    EXPECT_EQ(test::codes(b), std::vector<std::string>{"E0104"});
  }
}

// `grating period 1e-320 mm` compiled with a warning and stopped the servo at its first tick
// (force_not_finite). Absurd magnitudes are refused where they are written; periods finer than the
// device resolves, by the code generator.
TEST(HostileInput, PeriodsTheDeviceCannotPlayAreRefused) {
  const auto compile = [](const std::string& period, const std::string& device = "sim") {
    compiler::CompileOptions o;
    o.device = device;
    return compiler::Compiler(o).compile_text("grating period " + period + " amplitude 1 N", "<p>");
  };
  EXPECT_EQ(test::codes(compile("1e-320 mm")), std::vector<std::string>{"E0103"});
  EXPECT_EQ(test::codes(compile("1e300 mm")), std::vector<std::string>{"E0103"});
  EXPECT_EQ(test::codes(compile("0.0005 mm")), std::vector<std::string>{"E0304"});  // 0.5 um
  EXPECT_TRUE(compile("0.002 mm").ok());                                               // 2 um on sim
  // The 1995 joystick counts 0.0558 mm: a period needs two counts.
  EXPECT_EQ(test::codes(compile("0.1 mm", "sandpaper-1995")), std::vector<std::string>{"E0304"});
  EXPECT_TRUE(compile("0.2 mm", "sandpaper-1995").ok());
}

// Fuzz finding F1: a thesis stimulus name's kernel got no bound, and a huge one overflowed the blur
// radius's int (undefined behaviour). The name now says why it cannot be made.
TEST(HostileInput, AThesisNameWithAHugeKernelIsRefused) {
  const auto r = test::shipped_compiler().compile_text("like gridB5W5_17777777777777777777777777777777777777777", "<f1>");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0301"});
  EXPECT_NE(compiler::format_diagnostics(r.diagnostics).find("more than the largest kernel, 256 px"), std::string::npos)
      << compiler::format_diagnostics(r.diagnostics);
  EXPECT_TRUE(test::shipped_compiler().compile_text("like gridB5W5_2", "<ok>").ok());
}

// Fuzz finding F10: a 915 px grid tile under a 222 px kernel was within the first smoothing budget
// (2e9 multiply-adds) and took 5 s to compile, over 25 s under ASan. The budget is now 2e8, fifty
// times the largest thesis stimulus' smoothing; a tile a third the size still compiles.
TEST(HostileInput, ASmoothingPastTheBudgetIsRefusedBeforeItRuns) {
  const auto r = test::shipped_compiler().compile_text("like gridB10W905_222", "<f10>");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0301"});
  EXPECT_NE(compiler::format_diagnostics(r.diagnostics).find("past the pattern limits (E0304"), std::string::npos)
      << compiler::format_diagnostics(r.diagnostics);
  // The same tile written as a pattern statement says which limit.
  const auto p = test::shipped_compiler().compile_text(
      "pattern grid valley 1 mm hill 90.5 mm pixel 0.1 mm kernel 222 amplitude 1 N", "<f10-pattern>");
  ASSERT_EQ(test::codes(p), std::vector<std::string>{"E0304"});
  EXPECT_NE(compiler::format_diagnostics(p.diagnostics).find("915 x 915 px tile with kernel 222 would take too long"),
            std::string::npos)
      << compiler::format_diagnostics(p.diagnostics);
  EXPECT_TRUE(test::shipped_compiler()
                  .compile_text("pattern grid valley 1 mm hill 30 mm pixel 0.1 mm kernel 222 amplitude 1 N", "<ok>")
                  .ok());
}

// Fuzz finding F12: a tile's sides were bounded (4096 px) but not its area, and `gridB4000W95off5`
// made a 4095 x 8190 px tile: 8.8 s, 1.2 GB and a 268 MB patch. A tile or array is now at most
// 2048 x 2048 px in all; a 1599 x 1599 tile (gridB1598W1) still compiles.
TEST(HostileInput, APatternArrayPastItsAreaIsRefusedBeforeAllocating) {
  const auto r = test::shipped_compiler().compile_text("like gridB4000W95off5", "<f12>");
  ASSERT_EQ(test::codes(r), std::vector<std::string>{"E0301"});
  EXPECT_NE(compiler::format_diagnostics(r.diagnostics).find("past the pattern limits (E0304"), std::string::npos)
      << compiler::format_diagnostics(r.diagnostics);
  const auto p = test::shipped_compiler().compile_text("pattern grid valley 1 mm hill 300 mm pixel 0.1 mm amplitude 1 N", "<f12-pattern>");
  ASSERT_EQ(test::codes(p), std::vector<std::string>{"E0304"});
  EXPECT_NE(compiler::format_diagnostics(p.diagnostics).find("3010 x 3010 px, over 4194304 px in all"), std::string::npos)
      << compiler::format_diagnostics(p.diagnostics);
  const auto q = test::shipped_compiler().compile_text(
      "pattern perlin feature 1 mm pixel 0.05 mm amplitude 1 N; size 120 mm", "<f12-perlin>");
  ASSERT_EQ(test::codes(q), std::vector<std::string>{"E0304"});
  EXPECT_NE(compiler::format_diagnostics(q.diagnostics).find("over 4194304 px in all"), std::string::npos)
      << compiler::format_diagnostics(q.diagnostics);
  EXPECT_TRUE(test::shipped_compiler().compile_text("like gridB1598W1", "<ok>").ok());
}

// --- images ---

fs::path material_with_image(const fs::path& dir, const std::string& image) {
  const fs::path m = dir / "m.hmat";
  write(m, "material \"m\" {\n  heightmap \"" + image + "\" size 50 mm\n  roughness 0.5\n}\n");
  return m;
}

// A little-endian TIFF header that claims width x height pixels of `channels` 8-bit samples, with
// no pixel data at all: what a hostile 320-byte file looks like.
std::string tiff_claiming(std::uint32_t width, std::uint32_t height, std::uint16_t channels) {
  std::string t("II\x2A\0\x08\0\0\0", 8);
  const auto u16 = [&](std::uint32_t v) { t += static_cast<char>(v & 0xFF), t += static_cast<char>((v >> 8) & 0xFF); };
  const auto u32 = [&](std::uint32_t v) {
    for (int i = 0; i < 4; ++i) t += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t value;
  };
  const std::uint32_t data = 8 + 2 + 10 * 12 + 4;
  const Entry entries[] = {{256, 4, width}, {257, 4, height}, {258, 3, 8},  {259, 3, 1},     {262, 3, 1},
                           {273, 4, data},  {277, 3, channels}, {278, 4, height}, {279, 4, width * height}, {284, 3, 1}};
  u16(10);
  for (const auto& e : entries) {
    u16(e.tag), u16(e.type), u32(1);
    if (e.type == 3) u16(e.value), u16(0);
    else u32(e.value);
  }
  u32(0);
  t += std::string(200, '\0');
  return t;
}

TEST(HostileInput, AnImageHeaderClaimingHugeChannelsIsRefusedBeforeAllocating) {
  const fs::path dir = test::temp_dir("tiff-channels");
  for (const std::uint16_t channels : {std::uint16_t{40}, std::uint16_t{1000}}) {
    write(dir / "claims.tif", tiff_claiming(4096, 4096, channels));
    const auto before = peak_rss_bytes();
    const auto r = test::shipped_compiler().compile_file(material_with_image(dir, "claims.tif"));
    EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0402"}) << channels << " channels\n"
                                                                  << compiler::format_diagnostics(r.diagnostics);
    // It used to reach 2.8 GB for 40 channels, and std::bad_alloc for 1000.
    EXPECT_LT(peak_rss_bytes() - before, std::uint64_t{100} << 20) << channels << " channels";
  }
}

// A 8-bit grey TIFF with a slope in x, written by OpenImageIO.
void write_ramp_tiff(const fs::path& p, int n) {
  auto out = OIIO::ImageOutput::create(p.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(n, n, 1, OIIO::TypeDesc::UINT8);
  spec.attribute("tiff:RowsPerStrip", 1);
  std::vector<unsigned char> px(static_cast<std::size_t>(n) * n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) px[static_cast<std::size_t>(y) * n + x] = static_cast<unsigned char>((x * 7 + y * 3) % 256);
  ASSERT_TRUE(out->open(p.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, px.data()));
  out->close();
}

// A truncated TIFF used to compile with exit 0 and the missing rows silently zero: OpenImageIO
// reports success and only logs the error.
TEST(HostileInput, ATruncatedImageIsAnError) {
  const fs::path dir = test::temp_dir("tiff-truncated");
  write_ramp_tiff(dir / "ramp.tif", 128);
  ASSERT_TRUE(test::shipped_compiler().compile_file(material_with_image(dir, "ramp.tif")).ok());
  fs::resize_file(dir / "ramp.tif", fs::file_size(dir / "ramp.tif") / 2);
  const auto r = test::shipped_compiler().compile_file(material_with_image(dir, "ramp.tif"));
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0401"}) << compiler::format_diagnostics(r.diagnostics);
}

// `heightmap "/dev/zero"` used to hang (a format probe reads forever), and a FIFO blocks.
TEST(HostileInput, DevicesAndFifosAreNotRead) {
  const fs::path dir = test::temp_dir("devices");
  auto r = test::shipped_compiler().compile_file(material_with_image(dir, "/dev/zero"));
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0401"});
  ASSERT_EQ(mkfifo((dir / "pipe.png").c_str(), 0600), 0);
  r = test::shipped_compiler().compile_file(material_with_image(dir, "pipe.png"));
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0401"});
  ASSERT_EQ(mkfifo((dir / "pipe.hmat").c_str(), 0600), 0);
  r = test::shipped_compiler().compile_file(dir / "pipe.hmat");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0001"});
  r = test::shipped_compiler().compile_file("/dev/zero");
  EXPECT_EQ(test::codes(r), std::vector<std::string>{"E0001"});
}

}  // namespace
}  // namespace sandpaper
