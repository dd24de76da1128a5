#include "sandpaper/schema/patch_io.hpp"

#include "sandpaper/schema/input_limits.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <cstring>
#include <string>
#include <fstream>
#include <iterator>
#include <type_traits>
#include <variant>

#include <zlib.h>

// Header-only use of Imath's binary16 conversions (no lookup table, so nothing to link): the
// patch reader stays free of image libraries.
#define IMATH_HALF_NO_LOOKUP_TABLE
#include <Imath/half.h>

#include "patch_bytes.hpp"
#include "sandpaper/schema/atomic_file.hpp"
#include "sandpaper/schema/no_coverage.hpp"
#include "sandpaper/schema/term_kinds.hpp"

namespace sandpaper::schema {
namespace {

using namespace patch_bytes;

constexpr char kMagic[8] = {'S', 'N', 'D', 'P', 'A', 'T', 'C', 'H'};
constexpr std::size_t kHeaderSize = 32;
// A patch larger than this is not one the compiler makes (heightmaps are capped far below it).
constexpr std::uint64_t kMaxPayload = 1ull << 31;

static_assert(std::endian::native == std::endian::little, "patch I/O assumes a little-endian host");

// The per-sample loops of compact grids, apart so that the fuzzing build leaves them uninstrumented
// (no_coverage.hpp): in the material target they were a fifth of its time. The branch on the
// result stays in compact(), instrumented.

// grid as binary16 into out; false at the first force that moves by more than kCompactTolerance of
// peak (or overflows the half range). `error` gets the largest relative error up to there.
SANDPAPER_NO_COVERAGE bool to_halves(const float* grid, std::size_t n, double peak, std::uint16_t* out, double& error) {
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = imath_float_to_half(grid[i]);
    const double back = imath_half_to_float(out[i]);
    const double e = peak > 0 ? std::abs(back - grid[i]) / peak : (back == grid[i] ? 0.0 : 1.0);
    if (!(e <= kCompactTolerance)) return false;
    error = std::max(error, e);
  }
  return true;
}


// A grid as binary16, or nothing if some force would move by more than kCompactTolerance of the
// grid's largest component (or overflow the half range); `error` gets the largest relative error.
std::optional<std::vector<std::uint16_t>> compact(const std::vector<float>& grid, double peak, double& error) {
  std::vector<std::uint16_t> out(grid.size());
  if (!to_halves(grid.data(), grid.size(), peak, out.data(), error)) return std::nullopt;
  return out;
}

double largest_component(const std::vector<float>& a, const std::vector<float>& b) {
  double m = 0;
  for (float v : a) m = std::max(m, static_cast<double>(std::abs(v)));
  for (float v : b) m = std::max(m, static_cast<double>(std::abs(v)));
  return m;
}

// A listed field's bytes, by its member's type (docs/PATCH_FORMAT.md, "Terms").
template <class M>
void put(Writer& w, const M& v) {
  if constexpr (std::is_same_v<M, double>) {
    w.pod(v);
  } else if constexpr (std::is_same_v<M, double[2]>) {
    w.pod(v[0]);
    w.pod(v[1]);
  } else if constexpr (std::is_same_v<M, bool>) {
    w.pod<std::uint8_t>(v ? 1 : 0);
  } else {
    static_assert(std::is_enum_v<M> && sizeof(M) == 1, "a listed field is a double, a pair, a bool or a u8 enumeration");
    w.pod<std::uint8_t>(static_cast<std::uint8_t>(v));
  }
}

template <class T, class M>
void get(Reader& r, const terms::Field<T, M>& f, T& term) {
  M& v = term.*(f.member);
  if constexpr (std::is_same_v<M, double>) {
    v = r.pod<double>();
  } else if constexpr (std::is_same_v<M, double[2]>) {
    v[0] = r.pod<double>();
    v[1] = r.pod<double>();
  } else if constexpr (std::is_same_v<M, bool>) {
    v = r.pod<std::uint8_t>() != 0;
  } else {
    const auto raw = r.pod<std::uint8_t>();
    if (raw >= terms::EnumNames<M>::names.size())
      throw PatchFormatError(std::string(terms::Kind<T>::label) + " term with unknown " + std::string(f.label) + " " +
                             std::to_string(raw));
    v = static_cast<M>(raw);
  }
}

// The kinds without a field list.

void write_body(Writer& w, const GratingTerm& g, const PatchWriteOptions&, CompactReport*) {
  w.pod<std::uint32_t>(terms::Kind<GratingTerm>::tag);
  w.pod(g.period_m);
  w.pod(g.orientation_rad);
  w.floats(g.force_N);
}

void write_body(Writer& w, const HeightFieldTerm& h, const PatchWriteOptions& options, CompactReport* report) {
  std::optional<std::vector<std::uint16_t>> hx, hy;
  double error = 0;
  if (options.compact_grids) {
    const double peak = largest_component(h.force_x_N, h.force_y_N);
    hx = compact(h.force_x_N, peak, error);
    if (hx) hy = compact(h.force_y_N, peak, error);
    if (report != nullptr) {
      if (hx && hy) {
        ++report->compacted;
        report->largest_error = std::max(report->largest_error, error);
      } else {
        ++report->kept;
      }
    }
  }
  const bool half = hx && hy;
  w.pod<std::uint32_t>(half ? terms::Kind<HeightFieldTerm>::compact_tag : terms::Kind<HeightFieldTerm>::tag);
  w.pod(h.nx);
  w.pod(h.ny);
  w.pod(h.origin_m[0]);
  w.pod(h.origin_m[1]);
  w.pod(h.spacing_m[0]);
  w.pod(h.spacing_m[1]);
  w.pod<std::uint8_t>(h.repeat ? 1 : 0);
  if (half) {
    w.halves(std::move(*hx));
    w.halves(std::move(*hy));
  } else {
    w.floats(h.force_x_N);
    w.floats(h.force_y_N);
  }
}

// Both slots are written whatever the count, so the record has one fixed size.
void write_body(Writer& w, const PointMassesTerm& pm, const PatchWriteOptions&, CompactReport*) {
  w.pod<std::uint32_t>(terms::Kind<PointMassesTerm>::tag);
  w.pod(pm.count);
  for (int i = 0; i < 2; ++i) {
    w.pod(pm.mass_kg[i]);
    w.pod(pm.stiffness_N_per_m[i]);
    w.pod(pm.damping_Ns_per_m[i]);
  }
  w.pod(pm.ground_damping_Ns_per_m);
  w.pod(pm.gravity_m_s2[0]);
  w.pod(pm.gravity_m_s2[1]);
}

template <terms::Listed T>
void write_body(Writer& w, const T& term, const PatchWriteOptions&, CompactReport*) {
  w.pod<std::uint32_t>(terms::Kind<T>::tag);
  terms::for_each_field<T>([&](const auto& f) { put(w, term.*(f.member)); });
}

GratingTerm read_body(Reader& r, std::uint32_t, std::type_identity<GratingTerm>) {
  GratingTerm g;
  g.period_m = r.pod<double>();
  g.orientation_rad = r.pod<double>();
  g.force_N = r.floats();
  if (g.force_N.size() < 2 || !(g.period_m > 0) || !std::isfinite(g.period_m) || !std::isfinite(g.orientation_rad))
    throw PatchFormatError("grating term with no force table or a non-positive period");
  return g;
}

HeightFieldTerm read_body(Reader& r, std::uint32_t tag, std::type_identity<HeightFieldTerm>) {
  const bool half = tag == terms::Kind<HeightFieldTerm>::compact_tag;
  HeightFieldTerm h;
  h.nx = r.pod<std::uint32_t>();
  h.ny = r.pod<std::uint32_t>();
  h.origin_m[0] = r.pod<double>();
  h.origin_m[1] = r.pod<double>();
  h.spacing_m[0] = r.pod<double>();
  h.spacing_m[1] = r.pod<double>();
  h.repeat = r.pod<std::uint8_t>() != 0;
  h.force_x_N = half ? r.halves() : r.floats();
  h.force_y_N = half ? r.halves() : r.floats();
  auto n = static_cast<std::uint64_t>(h.nx) * h.ny;
  // One sample across is a field constant along that axis, which only a repeating field can mean
  // (the version-1 bars are 35 x 1 and repeat); a field that ends needs two samples to span a cell.
  const std::uint32_t least = h.repeat ? 1 : 2;
  if (h.nx < least || h.ny < least || h.force_x_N.size() != n || h.force_y_N.size() != n ||
      !(h.spacing_m[0] > 0) || !(h.spacing_m[1] > 0) || !std::isfinite(h.spacing_m[0]) ||
      !std::isfinite(h.spacing_m[1]) || !std::isfinite(h.origin_m[0]) || !std::isfinite(h.origin_m[1]))
    throw PatchFormatError("height-field term whose grid does not match its size");
  return h;
}

PointMassesTerm read_body(Reader& r, std::uint32_t, std::type_identity<PointMassesTerm>) {
  PointMassesTerm pm;
  pm.count = r.pod<std::uint32_t>();
  if (pm.count != 1 && pm.count != 2)
    throw PatchFormatError("point-masses term with " + std::to_string(pm.count) + " masses (1 or 2)");
  for (int i = 0; i < 2; ++i) {
    pm.mass_kg[i] = r.pod<double>();
    pm.stiffness_N_per_m[i] = r.pod<double>();
    pm.damping_Ns_per_m[i] = r.pod<double>();
  }
  pm.ground_damping_Ns_per_m = r.pod<double>();
  pm.gravity_m_s2[0] = r.pod<double>();
  pm.gravity_m_s2[1] = r.pod<double>();
  return pm;
}

template <terms::Listed T>
T read_body(Reader& r, std::uint32_t, std::type_identity<T>) {
  T term;
  terms::for_each_field<T>([&](const auto& f) { get(r, f, term); });
  return term;
}

template <class T>
constexpr bool has_tag(std::uint32_t tag) {
  if constexpr (requires { terms::Kind<T>::compact_tag; })
    if (tag == terms::Kind<T>::compact_tag) return true;
  return tag == terms::Kind<T>::tag;
}

void write_term(Writer& w, const Term& term, const PatchWriteOptions& options, CompactReport* report) {
  std::visit([&](const auto& t) { write_body(w, t, options, report); }, term);
}

Term read_term(Reader& r) {
  const auto tag = r.pod<std::uint32_t>();
  std::optional<Term> term;
  terms::for_each_kind([&]<class T>(std::type_identity<T> kind) {
    if (!term && has_tag<T>(tag)) term.emplace(read_body(r, tag, kind));
  });
  if (!term) throw PatchFormatError("unknown term tag " + std::to_string(tag) + " (made by a newer compiler?)");
  return std::move(*term);
}

}  // namespace

namespace {

// A patch names no absolute path of the machine that compiled it (docs/PATCH_FORMAT.md): a material
// file or image given by absolute path is named by its file name alone in the text a patch carries.
// An absolute path here starts a string or follows a space, quote or parenthesis, and runs to the
// next space, colon, quote or parenthesis ("/home/u/m.hmat:9:48" -> "m.hmat:9:48").
std::string without_machine_paths(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const bool starts = s[i] == '/' && i + 1 < s.size() && s[i + 1] != ' ' && s[i + 1] != '/' &&
                        (i == 0 || s[i - 1] == ' ' || s[i - 1] == '"' || s[i - 1] == '\'' || s[i - 1] == '(');
    if (!starts) {
      out += s[i++];
      continue;
    }
    std::size_t end = i, name = i + 1;
    while (end < s.size() && s[end] != ' ' && s[end] != ':' && s[end] != '"' && s[end] != '\'' && s[end] != ')') {
      if (s[end] == '/') name = end + 1;
      ++end;
    }
    out.append(s, name, end - name);
    i = end;
  }
  return out;
}

void write_payload(Writer& w, const PatchProgram& p, const PatchWriteOptions& options, CompactReport* report) {
  w.str(p.name);
  w.str(without_machine_paths(p.describes));
  w.str(p.device);
  w.str(without_machine_paths(p.command.device_file));
  w.str(p.command.command_unit);
  w.pod(p.command.newtons_per_command_unit[0]);
  w.pod(p.command.newtons_per_command_unit[1]);
  w.pod<std::int64_t>(p.command.command_max);
  w.pod(p.command.max_force_N);
  w.pod<std::uint8_t>(p.command.calibrated ? 1 : 0);
  w.pod(p.size_m[0]);
  w.pod(p.size_m[1]);
  w.pod(p.max_lateral_force_N);
  w.pod(p.roughness);
  w.str(p.roughness_map);
  w.str(without_machine_paths(p.roughness_map_file));
  w.pod(p.energy_budget_J);
  w.pod(p.energy_refill_W);
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(p.terms.size()));
  for (const auto& t : p.terms) write_term(w, t, options, report);
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(p.provenance.size()));
  for (const auto& pv : p.provenance) {
    w.str(pv.parameter);
    w.pod(pv.value_si);
    w.str(pv.si_unit);
    w.str(without_machine_paths(pv.stated));
    w.str(pv.layer);
    w.str(without_machine_paths(pv.source));
  }
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(p.warnings.size()));
  for (const auto& wn : p.warnings) {
    w.str(wn.code);
    w.str(without_machine_paths(wn.message));
  }
}

PatchProgram read_payload(Reader& r) {
  PatchProgram p;
  p.name = r.str();
  p.describes = r.str();
  p.device = r.str();
  p.command.device_file = r.str();
  p.command.command_unit = r.str();
  p.command.newtons_per_command_unit[0] = r.pod<double>();
  p.command.newtons_per_command_unit[1] = r.pod<double>();
  p.command.command_max = r.pod<std::int64_t>();
  p.command.max_force_N = r.pod<double>();
  p.command.calibrated = r.pod<std::uint8_t>() != 0;
  p.size_m[0] = r.pod<double>();
  p.size_m[1] = r.pod<double>();
  p.max_lateral_force_N = r.pod<double>();
  p.roughness = r.pod<double>();
  p.roughness_map = r.str();
  p.roughness_map_file = r.str();
  p.energy_budget_J = r.pod<double>();
  p.energy_refill_W = r.pod<double>();
  auto nterms = r.pod<std::uint32_t>();
  for (std::uint32_t i = 0; i < nterms; ++i) p.terms.push_back(read_term(r));
  auto nprov = r.pod<std::uint32_t>();
  for (std::uint32_t i = 0; i < nprov; ++i) {
    Provenance pv;
    pv.parameter = r.str();
    pv.value_si = r.pod<double>();
    pv.si_unit = r.str();
    pv.stated = r.str();
    pv.layer = r.str();
    pv.source = r.str();
    p.provenance.push_back(std::move(pv));
  }
  auto nwarn = r.pod<std::uint32_t>();
  for (std::uint32_t i = 0; i < nwarn; ++i) {
    CompileWarning wn;
    wn.code = r.str();
    wn.message = r.str();
    p.warnings.push_back(std::move(wn));
  }
  if (!r.done()) throw PatchFormatError("patch program has trailing bytes");
  // What the runtime would refuse is refused here, as a file error: a program with a NaN size has a
  // valid checksum but is still a bad file, not a bad command line (exit 1).
  const auto finite = [](double v) { return std::isfinite(v); };
  if (!(finite(p.size_m[0]) && p.size_m[0] > 0 && finite(p.size_m[1]) && p.size_m[1] > 0))
    throw PatchFormatError("patch program whose size is not positive and finite");
  if (!(finite(p.energy_budget_J) && p.energy_budget_J >= 0 && finite(p.energy_refill_W) && p.energy_refill_W >= 0))
    throw PatchFormatError("patch program whose energy budget or refill is negative or not finite");
  if (!(finite(p.max_lateral_force_N) && finite(p.roughness) && finite(p.command.max_force_N) &&
        finite(p.command.newtons_per_command_unit[0]) && finite(p.command.newtons_per_command_unit[1])))
    throw PatchFormatError("patch program with a non-finite force, roughness or command scale");
  return p;
}

struct Header {
  std::uint64_t size = 0;
  std::uint32_t crc = 0;
};

std::vector<unsigned char> header_bytes(std::uint64_t size, std::uint32_t crc) {
  std::vector<unsigned char> h(kHeaderSize, 0);  // flags (12..15) and padding (28..31) stay 0
  const std::uint32_t version = kPatchFormatVersion;
  std::memcpy(h.data(), kMagic, sizeof kMagic);
  std::memcpy(h.data() + 8, &version, sizeof version);
  std::memcpy(h.data() + 16, &size, sizeof size);
  std::memcpy(h.data() + 24, &crc, sizeof crc);
  return h;
}

// Checks the 32-byte header of a `total`-byte file and returns its payload size and checksum.
Header parse_header(const unsigned char* bytes, std::size_t total) {
  if (total < kHeaderSize || std::memcmp(bytes, kMagic, sizeof kMagic) != 0)
    throw PatchFormatError("not a Sandpaper patch program (no SNDPATCH header)");
  MemorySource source(bytes + 8, kHeaderSize - 8);
  Reader h(source);
  auto version = h.pod<std::uint32_t>();
  h.pod<std::uint32_t>();
  Header out;
  out.size = h.pod<std::uint64_t>();
  out.crc = h.pod<std::uint32_t>();
  if (version != kPatchFormatVersion)
    throw PatchFormatError("patch format version " + std::to_string(version) + ", this build reads version " +
                           std::to_string(kPatchFormatVersion) + ": recompile the material");
  if (out.size > kMaxPayload || out.size != total - kHeaderSize)
    throw PatchFormatError("patch program size does not match its header (truncated or padded file)");
  return out;
}

std::uint32_t crc_of_parts(const std::vector<std::string_view>& parts) {
  uLong c = crc32(0L, Z_NULL, 0);
  for (const auto& part : parts) {
    const auto* p = reinterpret_cast<const unsigned char*>(part.data());
    for (std::size_t done = 0; done < part.size();) {
      const auto chunk = static_cast<uInt>(std::min<std::size_t>(part.size() - done, 1u << 30));
      c = crc32(c, p + done, chunk);
      done += chunk;
    }
  }
  return static_cast<std::uint32_t>(c);
}

}  // namespace

std::vector<unsigned char> serialize(const PatchProgram& p, const PatchWriteOptions& options, CompactReport* report) {
  Writer w;
  write_payload(w, p, options, report);
  const auto parts = w.parts();
  auto out = header_bytes(w.size(), crc_of_parts(parts));
  out.reserve(out.size() + w.size());
  for (const auto& part : parts) {
    // As bytes of the vector's own type, so the copy is one memmove rather than a loop.
    const auto* b = reinterpret_cast<const unsigned char*>(part.data());
    out.insert(out.end(), b, b + part.size());
  }
  return out;
}

PatchProgram deserialize(const std::vector<unsigned char>& bytes) {
  const Header header = parse_header(bytes.data(), bytes.size());
  const unsigned char* payload = bytes.data() + kHeaderSize;
  if (crc_of(payload, header.size) != header.crc) throw PatchFormatError("patch program checksum mismatch (corrupted file)");
  MemorySource source(payload, header.size);
  Reader r(source);
  return read_payload(r);
}

void write_patch_file(const std::filesystem::path& path, const PatchProgram& program, const PatchWriteOptions& options,
                      CompactReport* report) {
  Writer w;
  write_payload(w, program, options, report);
  auto parts = w.parts();
  const auto header = header_bytes(w.size(), crc_of_parts(parts));
  parts.insert(parts.begin(), std::string_view(reinterpret_cast<const char*>(header.data()), header.size()));
  write_file_atomically(path, parts);
}

PatchProgram read_patch_file(const std::filesystem::path& path) {
  // Before opening: a FIFO or a device would block or never end.
  std::error_code ec;
  if (const auto status = std::filesystem::status(path, ec); !ec && std::filesystem::exists(status) &&
                                                             !std::filesystem::is_regular_file(status))
    throw PatchFormatError(path.string() + ": not a regular file");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw std::runtime_error("cannot open patch program '" + path.string() + "'");
  try {
    struct stat st{};
    if (fstat(fileno(f.get()), &st) != 0 || !S_ISREG(st.st_mode))
      throw PatchFormatError("not a regular file");
    unsigned char head[kHeaderSize] = {};
    const std::size_t got = std::fread(head, 1, kHeaderSize, f.get());
    const Header header = parse_header(head, got < kHeaderSize ? got : static_cast<std::size_t>(st.st_size));
    // Read in place into the program's arrays; the checksum is summed on the way and compared
    // before the program is returned, so a corrupted file is never used.
    FileSource source(f.get(), header.size);
    Reader r(source);
    PatchProgram program = read_payload(r);
    if (source.crc() != header.crc) throw PatchFormatError("patch program checksum mismatch (corrupted file)");
    return program;
  } catch (const PatchFormatError& e) {
    throw PatchFormatError(path.string() + ": " + e.what());
  }
}

bool looks_like_patch_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;  // a FIFO would block the open
  std::ifstream in(path, std::ios::binary);
  char m[8] = {};
  in.read(m, 8);
  return in.gcount() == 8 && std::memcmp(m, kMagic, 8) == 0;
}

}  // namespace sandpaper::schema
