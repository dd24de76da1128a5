#include "sandpaper/schema/patch_io.hpp"

#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <type_traits>
#include <variant>

#include <zlib.h>

#include "sandpaper/schema/atomic_file.hpp"

namespace sandpaper::schema {
namespace {

constexpr char kMagic[8] = {'S', 'N', 'D', 'P', 'A', 'T', 'C', 'H'};
constexpr std::size_t kHeaderSize = 32;
// A patch larger than this is not one the compiler makes (heightmaps are capped far below it).
constexpr std::uint64_t kMaxPayload = 1ull << 31;

static_assert(std::endian::native == std::endian::little, "patch I/O assumes a little-endian host");

// Payload tags: one per term kind; stable across versions (docs/PATCH_FORMAT.md).
enum : std::uint32_t {
  kTagSpring = 1,
  kTagDamper = 2,
  kTagGrating = 3,
  kTagHeightField = 4,
  kTagConstantForce = 5,
  kTagNap = 6,
  kTagPeriodic = 7,
  kTagRidge = 8,
  kTagBowl = 9,
  kTagLinearField = 10,
  kTagLinearSpring = 11,
  kTagMinus = 12,
  kTagFollowerSpring = 13,
  kTagPointMasses = 14,
  kTagAttractor = 15,
};
static_assert(std::variant_size_v<Term> == 15, "a new term kind needs a tag, a writer and a reader here");

class Writer {
 public:
  template <class T>
  void pod(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* b = reinterpret_cast<const unsigned char*>(&v);
    out_.insert(out_.end(), b, b + sizeof(T));
  }
  void str(const std::string& s) {
    pod<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    out_.insert(out_.end(), s.begin(), s.end());
  }
  void floats(const std::vector<float>& v) {
    pod<std::uint64_t>(v.size());
    const auto* b = reinterpret_cast<const unsigned char*>(v.data());
    out_.insert(out_.end(), b, b + v.size() * sizeof(float));
  }
  std::vector<unsigned char>& bytes() { return out_; }

 private:
  std::vector<unsigned char> out_;
};

class Reader {
 public:
  Reader(const unsigned char* p, std::size_t n) : p_(p), end_(p + n) {}
  template <class T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, p_, sizeof(T));
    p_ += sizeof(T);
    return v;
  }
  std::string str() {
    auto n = pod<std::uint32_t>();
    need(n);
    std::string s(reinterpret_cast<const char*>(p_), n);
    p_ += n;
    return s;
  }
  std::vector<float> floats() {
    auto n = pod<std::uint64_t>();
    if (n > static_cast<std::uint64_t>(end_ - p_) / sizeof(float))
      throw PatchFormatError("patch program truncated: float array longer than the file");
    std::vector<float> v(n);
    std::memcpy(v.data(), p_, n * sizeof(float));
    p_ += n * sizeof(float);
    return v;
  }
  bool done() const { return p_ == end_; }

 private:
  void need(std::size_t n) const {
    if (static_cast<std::size_t>(end_ - p_) < n) throw PatchFormatError("patch program truncated");
  }
  const unsigned char* p_;
  const unsigned char* end_;
};

std::uint32_t crc_of(const unsigned char* p, std::size_t n) {
  uLong c = crc32(0L, Z_NULL, 0);
  // zlib takes uInt lengths; feed in chunks so payloads over 4 GiB would still be summed right.
  while (n > 0) {
    auto chunk = static_cast<uInt>(std::min<std::size_t>(n, 1u << 30));
    c = crc32(c, p, chunk);
    p += chunk;
    n -= chunk;
  }
  return static_cast<std::uint32_t>(c);
}

void write_term(Writer& w, const Term& term) {
  if (const auto* s = std::get_if<SpringTerm>(&term)) {
    w.pod<std::uint32_t>(kTagSpring);
    w.pod(s->stiffness_N_per_m);
    w.pod(s->centre_m[0]);
    w.pod(s->centre_m[1]);
  } else if (const auto* d = std::get_if<DamperTerm>(&term)) {
    w.pod<std::uint32_t>(kTagDamper);
    w.pod(d->damping_Ns_per_m);
  } else if (const auto* g = std::get_if<GratingTerm>(&term)) {
    w.pod<std::uint32_t>(kTagGrating);
    w.pod(g->period_m);
    w.pod(g->orientation_rad);
    w.floats(g->force_N);
  } else if (const auto* h = std::get_if<HeightFieldTerm>(&term)) {
    w.pod<std::uint32_t>(kTagHeightField);
    w.pod(h->nx);
    w.pod(h->ny);
    w.pod(h->origin_m[0]);
    w.pod(h->origin_m[1]);
    w.pod(h->spacing_m[0]);
    w.pod(h->spacing_m[1]);
    w.pod<std::uint8_t>(h->repeat ? 1 : 0);
    w.floats(h->force_x_N);
    w.floats(h->force_y_N);
  } else if (const auto* c = std::get_if<ConstantForceTerm>(&term)) {
    w.pod<std::uint32_t>(kTagConstantForce);
    w.pod(c->force_N[0]);
    w.pod(c->force_N[1]);
  } else if (const auto* n = std::get_if<NapTerm>(&term)) {
    w.pod<std::uint32_t>(kTagNap);
    w.pod(n->damping_Ns_per_m);
  } else if (const auto* pe = std::get_if<PeriodicTerm>(&term)) {
    w.pod<std::uint32_t>(kTagPeriodic);
    w.pod<std::uint8_t>(static_cast<std::uint8_t>(pe->shape));
    w.pod(pe->amplitude_N);
    w.pod(pe->period_m);
    w.pod<std::uint8_t>(pe->on_x ? 1 : 0);
    w.pod<std::uint8_t>(pe->on_y ? 1 : 0);
  } else if (const auto* r = std::get_if<RidgeTerm>(&term)) {
    w.pod<std::uint32_t>(kTagRidge);
    w.pod(r->stiffness_N_per_m);
    w.pod(r->wavelength_m);
    w.pod(r->ridge_width_m);
  } else if (const auto* b = std::get_if<BowlTerm>(&term)) {
    w.pod<std::uint32_t>(kTagBowl);
    w.pod(b->stiffness_N_per_m);
    w.pod(b->radius_m);
  } else if (const auto* lf = std::get_if<LinearFieldTerm>(&term)) {
    w.pod<std::uint32_t>(kTagLinearField);
    w.pod(lf->radial_N_per_m);
    w.pod(lf->tangential_N_per_m);
  } else if (const auto* ls = std::get_if<LinearSpringTerm>(&term)) {
    w.pod<std::uint32_t>(kTagLinearSpring);
    w.pod(ls->stiffness_N_per_m);
    w.pod(ls->orientation_rad);
    w.pod(ls->centre_m[0]);
    w.pod(ls->centre_m[1]);
  } else if (const auto* mi = std::get_if<MinusTerm>(&term)) {
    w.pod<std::uint32_t>(kTagMinus);
    w.pod(mi->stiffness_N_per_m);
    w.pod(mi->lead_s);
  } else if (const auto* fs = std::get_if<FollowerSpringTerm>(&term)) {
    w.pod<std::uint32_t>(kTagFollowerSpring);
    w.pod(fs->stiffness_N_per_m);
    w.pod(fs->lag_s);
  } else if (const auto* pm = std::get_if<PointMassesTerm>(&term)) {
    // Both slots are written whatever the count, so the record has one fixed size.
    w.pod<std::uint32_t>(kTagPointMasses);
    w.pod(pm->count);
    for (int i = 0; i < 2; ++i) {
      w.pod(pm->mass_kg[i]);
      w.pod(pm->stiffness_N_per_m[i]);
      w.pod(pm->damping_Ns_per_m[i]);
    }
    w.pod(pm->ground_damping_Ns_per_m);
    w.pod(pm->gravity_m_s2[0]);
    w.pod(pm->gravity_m_s2[1]);
  } else if (const auto* a = std::get_if<AttractorTerm>(&term)) {
    w.pod<std::uint32_t>(kTagAttractor);
    w.pod(a->stiffness_N_per_m);
    w.pod(a->radius_m);
    w.pod(a->period_s);
    w.pod(a->swirl);
    w.pod(a->centre_m[0]);
    w.pod(a->centre_m[1]);
  }
}

Term read_term(Reader& r) {
  auto tag = r.pod<std::uint32_t>();
  switch (tag) {
    case kTagSpring: {
      SpringTerm s;
      s.stiffness_N_per_m = r.pod<double>();
      s.centre_m[0] = r.pod<double>();
      s.centre_m[1] = r.pod<double>();
      return s;
    }
    case kTagDamper: {
      DamperTerm d;
      d.damping_Ns_per_m = r.pod<double>();
      return d;
    }
    case kTagGrating: {
      GratingTerm g;
      g.period_m = r.pod<double>();
      g.orientation_rad = r.pod<double>();
      g.force_N = r.floats();
      if (g.force_N.size() < 2 || !(g.period_m > 0))
        throw PatchFormatError("grating term with no force table or a non-positive period");
      return g;
    }
    case kTagHeightField: {
      HeightFieldTerm h;
      h.nx = r.pod<std::uint32_t>();
      h.ny = r.pod<std::uint32_t>();
      h.origin_m[0] = r.pod<double>();
      h.origin_m[1] = r.pod<double>();
      h.spacing_m[0] = r.pod<double>();
      h.spacing_m[1] = r.pod<double>();
      h.repeat = r.pod<std::uint8_t>() != 0;
      h.force_x_N = r.floats();
      h.force_y_N = r.floats();
      auto n = static_cast<std::uint64_t>(h.nx) * h.ny;
      if (h.nx < 2 || h.ny < 2 || h.force_x_N.size() != n || h.force_y_N.size() != n ||
          !(h.spacing_m[0] > 0) || !(h.spacing_m[1] > 0))
        throw PatchFormatError("height-field term whose grid does not match its size");
      return h;
    }
    case kTagConstantForce: {
      ConstantForceTerm c;
      c.force_N[0] = r.pod<double>();
      c.force_N[1] = r.pod<double>();
      return c;
    }
    case kTagNap: {
      NapTerm n;
      n.damping_Ns_per_m = r.pod<double>();
      return n;
    }
    case kTagPeriodic: {
      PeriodicTerm pe;
      const auto shape = r.pod<std::uint8_t>();
      if (shape > static_cast<std::uint8_t>(PeriodicShape::Triangle))
        throw PatchFormatError("periodic term with unknown shape " + std::to_string(shape));
      pe.shape = static_cast<PeriodicShape>(shape);
      pe.amplitude_N = r.pod<double>();
      pe.period_m = r.pod<double>();
      pe.on_x = r.pod<std::uint8_t>() != 0;
      pe.on_y = r.pod<std::uint8_t>() != 0;
      return pe;
    }
    case kTagRidge: {
      RidgeTerm ri;
      ri.stiffness_N_per_m = r.pod<double>();
      ri.wavelength_m = r.pod<double>();
      ri.ridge_width_m = r.pod<double>();
      return ri;
    }
    case kTagBowl: {
      BowlTerm b;
      b.stiffness_N_per_m = r.pod<double>();
      b.radius_m = r.pod<double>();
      return b;
    }
    case kTagLinearField: {
      LinearFieldTerm lf;
      lf.radial_N_per_m = r.pod<double>();
      lf.tangential_N_per_m = r.pod<double>();
      return lf;
    }
    case kTagLinearSpring: {
      LinearSpringTerm ls;
      ls.stiffness_N_per_m = r.pod<double>();
      ls.orientation_rad = r.pod<double>();
      ls.centre_m[0] = r.pod<double>();
      ls.centre_m[1] = r.pod<double>();
      return ls;
    }
    case kTagMinus: {
      MinusTerm mi;
      mi.stiffness_N_per_m = r.pod<double>();
      mi.lead_s = r.pod<double>();
      return mi;
    }
    case kTagFollowerSpring: {
      FollowerSpringTerm fs;
      fs.stiffness_N_per_m = r.pod<double>();
      fs.lag_s = r.pod<double>();
      return fs;
    }
    case kTagPointMasses: {
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
    case kTagAttractor: {
      AttractorTerm a;
      a.stiffness_N_per_m = r.pod<double>();
      a.radius_m = r.pod<double>();
      a.period_s = r.pod<double>();
      a.swirl = r.pod<double>();
      a.centre_m[0] = r.pod<double>();
      a.centre_m[1] = r.pod<double>();
      return a;
    }
    default:
      throw PatchFormatError("unknown term tag " + std::to_string(tag) + " (made by a newer compiler?)");
  }
}

}  // namespace

std::vector<unsigned char> serialize(const PatchProgram& p) {
  Writer w;
  w.str(p.name);
  w.str(p.describes);
  w.str(p.device);
  w.str(p.command.device_file);
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
  w.str(p.roughness_map_file);
  w.pod(p.energy_budget_J);
  w.pod(p.energy_refill_W);
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(p.terms.size()));
  for (const auto& t : p.terms) write_term(w, t);
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(p.provenance.size()));
  for (const auto& pv : p.provenance) {
    w.str(pv.parameter);
    w.pod(pv.value_si);
    w.str(pv.si_unit);
    w.str(pv.stated);
    w.str(pv.layer);
    w.str(pv.source);
  }
  w.pod<std::uint32_t>(static_cast<std::uint32_t>(p.warnings.size()));
  for (const auto& wn : p.warnings) {
    w.str(wn.code);
    w.str(wn.message);
  }
  const auto& payload = w.bytes();

  Writer h;
  for (char c : kMagic) h.pod(c);
  h.pod<std::uint32_t>(kPatchFormatVersion);
  h.pod<std::uint32_t>(0);  // flags, reserved
  h.pod<std::uint64_t>(payload.size());
  h.pod<std::uint32_t>(crc_of(payload.data(), payload.size()));
  h.pod<std::uint32_t>(0);  // padding to 32 bytes
  auto out = std::move(h.bytes());
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

PatchProgram deserialize(const std::vector<unsigned char>& bytes) {
  if (bytes.size() < kHeaderSize || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw PatchFormatError("not a Sandpaper patch program (no SNDPATCH header)");
  Reader h(bytes.data() + 8, kHeaderSize - 8);
  auto version = h.pod<std::uint32_t>();
  h.pod<std::uint32_t>();
  auto size = h.pod<std::uint64_t>();
  auto crc = h.pod<std::uint32_t>();
  if (version != kPatchFormatVersion)
    throw PatchFormatError("patch format version " + std::to_string(version) + ", this build reads version " +
                           std::to_string(kPatchFormatVersion) + ": recompile the material");
  if (size > kMaxPayload || size != bytes.size() - kHeaderSize)
    throw PatchFormatError("patch program size does not match its header (truncated or padded file)");
  const unsigned char* payload = bytes.data() + kHeaderSize;
  if (crc_of(payload, size) != crc) throw PatchFormatError("patch program checksum mismatch (corrupted file)");

  Reader r(payload, size);
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
  return p;
}

void write_patch_file(const std::filesystem::path& path, const PatchProgram& program) {
  auto bytes = serialize(program);
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

PatchProgram read_patch_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open patch program '" + path.string() + "'");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    return deserialize(bytes);
  } catch (const PatchFormatError& e) {
    throw PatchFormatError(path.string() + ": " + e.what());
  }
}

bool looks_like_patch_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char m[8] = {};
  in.read(m, 8);
  return in.gcount() == 8 && std::memcmp(m, kMagic, 8) == 0;
}

}  // namespace sandpaper::schema
