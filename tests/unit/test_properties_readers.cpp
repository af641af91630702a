// Property tests (rapidcheck) of the file readers: NaN/Inf in CSV and NPY samples, finite directions
// of any size normalized, and random materials JSON in and out of the glTF domain.
#include "properties_support.hpp"

namespace {

// ---------------------------------------------------------------------------------------------
// File readers. Each test writes its files into its own temporary directory.

std::atomic<int> dirCounter{0};

class ReaderProperties : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("brdfcl-prop-" + std::to_string(::getpid()) + "-" + info->name() + "-" + std::to_string(dirCounter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& content) const {
    const std::string p = (dir_ / name).string();
    std::ofstream(p, std::ios::binary | std::ios::trunc) << content;
    return p;
  }
  fs::path dir_;
};

const char* const kColumns[] = {"material", "Lx", "Ly", "Lz", "Vx", "Vy", "Vz"};

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);  // round-trips a double exactly
  return buf;
}

// NPY v1.0 of `rows` x 7, float32 or float64, C or Fortran order; `cell(r, c)` gives the raw bits.
template <class Bits>
std::string npyFile(std::size_t rows, bool float32, bool fortran, Bits&& cell) {
  std::string header = std::string("{'descr': '") + (float32 ? "<f4" : "<f8") +
                       "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': (" + std::to_string(rows) +
                       ", 7), }";
  header.append(63 - (10 + header.size()) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  out += char(header.size() & 0xff);
  out += char(header.size() >> 8);
  out += header;
  for (std::size_t a = 0; a < (fortran ? 7 : rows); ++a)
    for (std::size_t b = 0; b < (fortran ? rows : 7); ++b) {
      const std::uint64_t bits = fortran ? cell(b, a) : cell(a, b);
      out.append(reinterpret_cast<const char*>(&bits), float32 ? 4 : 8);  // little-endian host
    }
  return out;
}

std::uint64_t bitsOf(double v, bool float32) {
  if (float32) {
    const float f = float(v);
    std::uint32_t b;
    std::memcpy(&b, &f, 4);
    return b;
  }
  std::uint64_t b;
  std::memcpy(&b, &v, 8);
  return b;
}

struct NonFinite {
  std::uint64_t bits32, bits64;  // the same value as float32 and float64 bit patterns
  const char* csv;               // one way to write it in CSV
  const char* shown;             // how the message prints it
};

void showValue(const NonFinite& n, std::ostream& os) { os << n.csv; }

// Quiet, signalling, negative and payload NaNs; infinities; CSV spellings from_chars and strtod
// accept, and 1e999, which overflows to inf.
rc::Gen<NonFinite> nonFinite() {
  return rc::gen::element(NonFinite{0x7fc00000u, 0x7ff8000000000000ull, "nan", "nan"},
                          NonFinite{0x7f800001u, 0x7ff0000000000001ull, "NaN", "nan"},
                          NonFinite{0xffc00000u, 0xfff8000000000000ull, "-nan", "nan"},
                          NonFinite{0x7fabcdefu, 0x7ff4000000abcdefull, "NAN", "nan"},
                          NonFinite{0x7f800000u, 0x7ff0000000000000ull, "inf", "inf"},
                          NonFinite{0x7f800000u, 0x7ff0000000000000ull, "+inf", "inf"},
                          NonFinite{0x7f800000u, 0x7ff0000000000000ull, "Infinity", "inf"},
                          NonFinite{0x7f800000u, 0x7ff0000000000000ull, "1e999", "inf"},
                          NonFinite{0xff800000u, 0xfff0000000000000ull, "-inf", "-inf"},
                          NonFinite{0xff800000u, 0xfff0000000000000ull, "-1e400", "-inf"});
}

// A valid sample row: a material index and two ordinary directions, exactly representable in float.
rc::Gen<std::array<double, 7>> validRow() {
  return rc::gen::exec([] {
    std::array<double, 7> r{};
    r[0] = *rc::gen::inRange(0, 3);
    for (int c = 1; c < 7; ++c) r[c] = *rc::gen::inRange(-256, 257) / 256.0;
    r[3] = r[6] = 0.5;  // never a zero-length direction
    return r;
  });
}

// NaN or Inf anywhere in a CSV samples file is refused with the file, the 1-based line, the
// column and the text as written: "s.csv:17: field 'Lx' is not finite: '1e999'".
TEST_F(ReaderProperties, CsvNonFiniteFieldIsRejectedWithFileLineAndColumn) {
  checkProperty(200, [this] {
    const auto rows = *rc::gen::resize(40, rc::gen::nonEmpty(rc::gen::container<std::vector<std::array<double, 7>>>(validRow())));
    const std::size_t row = *rc::gen::inRange<std::size_t>(0, rows.size());
    const int col = *rc::gen::inRange(0, 7);
    const NonFinite bad = *nonFinite();
    std::string text = "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (int c = 0; c < 7; ++c) text += (r == row && c == col ? std::string(bad.csv) : num(rows[r][c])) + (c < 6 ? "," : "\n");
    const std::string path = write("s.csv", text);
    std::string got;
    try {
      readSamples(path, 3, false);
    } catch (const Error& e) {
      got = e.what();
    }
    // CSV messages quote the field as written ('1e999'); NPY ones print the value.
    RC_ASSERT(got == path + ":" + std::to_string(row + 2) + ": field '" + kColumns[col] + "' is not finite: '" + bad.csv +
                         "'");
  });
}

// The same for NPY: float32 and float64, C and Fortran order, every NaN/Inf bit pattern;
// rows are 0-based as numpy counts them.
TEST_F(ReaderProperties, NpyNonFiniteValueIsRejectedWithFileRowAndColumn) {
  checkProperty(200, [this] {
    const auto rows = *rc::gen::resize(40, rc::gen::nonEmpty(rc::gen::container<std::vector<std::array<double, 7>>>(validRow())));
    const std::size_t row = *rc::gen::inRange<std::size_t>(0, rows.size());
    const int col = *rc::gen::inRange(0, 7);
    const NonFinite bad = *nonFinite();
    const bool float32 = *rc::gen::arbitrary<bool>(), fortran = *rc::gen::arbitrary<bool>();
    const std::string path = write("s.npy", npyFile(rows.size(), float32, fortran, [&](std::size_t r, std::size_t c) {
      return r == row && int(c) == col ? (float32 ? bad.bits32 : bad.bits64) : bitsOf(rows[r][c], float32);
    }));
    std::string got;
    try {
      readSamples(path, 3, false);
    } catch (const Error& e) {
      got = e.what();
    }
    RC_ASSERT(got == path + ": row " + std::to_string(row) + ": field '" + kColumns[col] + "' is not finite: " + bad.shown);
  });
}

// A direction component as a user might write it: any finite double (for CSV and float64 NPY)
// or float (float32 NPY), denormals and DBL_MAX included.
rc::Gen<double> fileComponent(bool float32) {
  if (float32) return rc::gen::map(component(), [](float f) { return double(f); });
  return rc::gen::weightedOneOf<double>({
      {3, rc::gen::map(component(), [](float f) { return double(f); })},
      {2, rc::gen::element(1e-310, -1e-310, 4.9406564584124654e-324, 1e300, -1e300, DBL_MAX, -DBL_MAX, 1e-300)},
      {3, rc::gen::map(rc::gen::inRange<std::uint64_t>(0, ~std::uint64_t(0)), [](std::uint64_t b) {
         if ((b & 0x7ff0000000000000ull) == 0x7ff0000000000000ull) b &= ~0x4000000000000000ull;  // finite
         double d;
         std::memcpy(&d, &b, 8);
         return d;
       })},
  });
}

using Raw = std::array<double, 3>;

rc::Gen<Raw> nonZeroRaw(bool float32) {
  return rc::gen::suchThat(rc::gen::exec([float32] { return Raw{*fileComponent(float32), *fileComponent(float32), *fileComponent(float32)}; }),
                           [](const Raw& r) { return r[0] != 0.0 || r[1] != 0.0 || r[2] != 0.0; });
}

// The unit vector with the direction of `raw`, in long double: what the reader should give, to
// float precision.
std::array<long double, 3> exactUnit(const Raw& raw) {
  const long double m = std::max({std::fabs((long double)raw[0]), std::fabs((long double)raw[1]), std::fabs((long double)raw[2])});
  std::array<long double, 3> u{raw[0] / m, raw[1] / m, raw[2] / m};
  const long double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (auto& c : u) c /= len;
  return u;
}

// Any finite, non-zero direction, however large or small its components, is accepted and
// normalized to unit length with its direction kept; the whole pipeline (reader, then
// evaluate) then gives finite f, 0 below the horizon.
TEST_F(ReaderProperties, FiniteNonZeroDirectionsAreNormalizedAndEvaluateToFiniteF) {
  checkProperty(150, [this] {
    const int format = *rc::gen::inRange(0, 3);  // CSV, float64 NPY, float32 NPY
    const bool float32 = format == 2;
    const auto n = *rc::gen::inRange(1, 25);
    std::vector<std::pair<Raw, Raw>> pairs;
    for (int i = 0; i < n; ++i) pairs.push_back({*nonZeroRaw(float32), *nonZeroRaw(float32)});
    std::string path;
    if (format == 0) {
      std::string text = "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
      for (int i = 0; i < n; ++i) {
        text += std::to_string(i % 2);
        for (const Raw* d : {&pairs[i].first, &pairs[i].second})
          for (double c : *d) text += "," + num(c);
        text += "\n";
      }
      path = write("s.csv", text);
    } else {
      path = write("s.npy", npyFile(std::size_t(n), float32, false, [&](std::size_t r, std::size_t c) {
        const double v = c == 0 ? double(r % 2) : c < 4 ? pairs[r].first[c - 1] : pairs[r].second[c - 4];
        return bitsOf(v, float32);
      }));
    }
    Samples s;
    try {
      s = readSamples(path, 2, false);
    } catch (const Error& e) {
      RC_FAIL(std::string("rejected: ") + e.what());
    }
    RC_ASSERT(s.size() == std::size_t(n));
    for (int i = 0; i < n; ++i)
      for (int which = 0; which < 2; ++which) {
        const float* got = which == 0 ? &s.L[3 * i] : &s.V[3 * i];
        const auto want = exactUnit(which == 0 ? pairs[i].first : pairs[i].second);
        const double len = std::sqrt(double(got[0]) * got[0] + double(got[1]) * got[1] + double(got[2]) * got[2]);
        RC_ASSERT(std::fabs(len - 1.0) < 1e-6);
        for (int c = 0; c < 3; ++c) RC_ASSERT(std::fabs((long double)got[c] - want[c]) < 1e-6L);
      }
    const auto f = evaluatorFor(EvalOptions{}).evaluate(featureCarriers(), s);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        RC_ASSERT(std::isfinite(f[3 * i + c]));
        if (!(s.L[3 * i + 2] > 0.0f) || !(s.V[3 * i + 2] > 0.0f)) RC_ASSERT(f[3 * i + c] == 0.0f);
      }
  });
}

// ---------------------------------------------------------------------------------------------
// Materials JSON. JSON has no NaN literal; what can go wrong is a number out of the glTF range,
// one too large for float, one beyond double (1e999) or a value of the wrong type.

enum class Range { Unit, NonNegative, Intensity, Finite };

struct Slot {
  std::vector<std::string> keys;  // JSON object keys from the material down
  int element;                    // index in the array, or -1 for a plain number
  Range range;
  std::string path() const {
    std::string p;
    for (const auto& k : keys) p += "." + k;
    return element < 0 ? p : p + "[" + std::to_string(element) + "]";
  }
};

const std::vector<Slot>& coreSlots() {
  static const std::vector<Slot> s = [] {
    std::vector<Slot> v;
    for (int c = 0; c < 4; ++c) v.push_back({{"pbrMetallicRoughness", "baseColorFactor"}, c, Range::Unit});
    v.push_back({{"pbrMetallicRoughness", "metallicFactor"}, -1, Range::Unit});
    v.push_back({{"pbrMetallicRoughness", "roughnessFactor"}, -1, Range::Unit});
    for (int c = 0; c < 3; ++c) v.push_back({{"emissiveFactor"}, c, Range::NonNegative});
    v.push_back({{"extensions", "KHR_materials_clearcoat", "clearcoatFactor"}, -1, Range::Unit});
    v.push_back({{"extensions", "KHR_materials_clearcoat", "clearcoatRoughnessFactor"}, -1, Range::Unit});
    v.push_back({{"extensions", "KHR_materials_anisotropy", "anisotropyStrength"}, -1, Range::Unit});
    v.push_back({{"extensions", "KHR_materials_anisotropy", "anisotropyRotation"}, -1, Range::Finite});
    return v;
  }();
  return s;
}

std::vector<Slot> sheenSlots(bool draft) {
  const std::vector<std::string> ext{"extensions", "KHR_materials_sheen"};
  auto key = [&](const char* k) { auto v = ext; v.push_back(k); return v; };
  if (draft)
    return {{key("intensityFactor"), -1, Range::Intensity}, {key("colorFactor"), 0, Range::Unit},
            {key("colorFactor"), 1, Range::Unit}, {key("colorFactor"), 2, Range::Unit}};
  return {{key("sheenColorFactor"), 0, Range::Unit}, {key("sheenColorFactor"), 1, Range::Unit},
          {key("sheenColorFactor"), 2, Range::Unit}, {key("sheenRoughnessFactor"), -1, Range::Unit}};
}

// In-range values as a file would hold them: doubles, so 1e-300 (0 as a float) and values that
// round to 1.0f are there too.
rc::Gen<double> inRange(Range r) {
  const auto unit = rc::gen::weightedOneOf<double>({
      {3, rc::gen::element(0.0, 1.0, 1e-300, 1e-40, 0.5, 0.99999999999, 4.9406564584124654e-324)},
      {5, rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 1000001), [](std::uint32_t k) { return k * 1e-6; })},
  });
  if (r == Range::Unit) return unit;
  if (r == Range::NonNegative)
    return rc::gen::weightedOneOf<double>({{4, unit}, {1, rc::gen::element(1e30, 3.4028234663852886e38, 7.0, 1e-310)}});
  if (r == Range::Intensity)
    return rc::gen::weightedOneOf<double>({{4, unit}, {1, rc::gen::element(1e30, 7e29, 7.0, 1e-310)}});
  return rc::gen::weightedOneOf<double>({
      {2, unit},
      {1, rc::gen::element(-1e30, 1e30, -3.4028234663852886e38, 3.4028234663852886e38, -7.5, 6283.185307179586)},
      {2, rc::gen::map(rc::gen::inRange<int>(-1000000, 1000001), [](int k) { return k * 1e-4; })},
  });
}

struct BadJson {
  std::string text;  // JSON text of the value
  std::string shown; // how the message describes it
};

void showValue(const BadJson& b, std::ostream& os) { os << b.text; }

rc::Gen<BadJson> badJson(Range r) {
  std::vector<BadJson> v = {{"\"0.5\"", "string \"0.5\""}, {"null", "null"}, {"true", "true"}, {"[0.5]", "an array of 1 element"}};
  if (r != Range::Finite) v.insert(v.end(), {{"-0.5", "-0.5"}, {"-1e-300", "-1e-300"}, {"-3", "-3"}});
  if (r == Range::Unit) v.insert(v.end(), {{"1.5", "1.5"}, {"2", "2"}, {"1.0000001", "1.0000001"}, {"1e300", "1e+300"}});
  if (r != Range::Unit) v.insert(v.end(), {{"1e300", "1e+300 (too large for float)"}, {"6.8e38", "6.8e+38 (too large for float)"}});
  if (r == Range::Intensity)
    v.insert(v.end(), {{"1e31", "1e+31 (at most 1e+30: f would overflow float)"},
                       {"3.4e38", "3.4e+38 (at most 1e+30: f would overflow float)"}});
  if (r == Range::Finite) v.push_back({"-1e300", "-1e+300 (too large for float)"});
  return rc::gen::elementOf(v);
}

const char* expectedText(Range r) {
  return r == Range::Unit ? "a number in [0, 1]" : r == Range::Finite ? "a finite number" : "a number >= 0";
}

float fieldOf(const MaterialParams& m, const Slot& s) {
  const std::string& k = s.keys.back();
  const int e = s.element;
  if (k == "baseColorFactor") return e < 3 ? m.baseColor[e] : NAN;  // alpha is checked, not kept
  if (k == "metallicFactor") return m.metallic;
  if (k == "roughnessFactor") return m.roughness;
  if (k == "emissiveFactor") return m.emissive[e];
  if (k == "clearcoatFactor") return m.clearcoat;
  if (k == "clearcoatRoughnessFactor") return m.clearcoatRoughness;
  if (k == "anisotropyStrength") return m.anisotropyStrength;
  if (k == "anisotropyRotation") return m.anisotropyRotation;
  if (k == "intensityFactor") return m.draftIntensity;
  if (k == "colorFactor") return m.draftColor[e];
  if (k == "sheenColorFactor") return m.sheenColor[e];
  return m.sheenRoughness;
}

// Random materials with a random subset of every factor: in-range values are read as the float
// nearest to them; one bad value in any of them is refused with the file, the JSON path and the
// value; 1e999 (beyond double) with the line it is on.
TEST_F(ReaderProperties, MaterialsJsonInRangeAcceptedOutOfRangeRejected) {
  checkProperty(250, [this] {
    const int count = *rc::gen::inRange(1, 5);
    struct Placed {
      int material;
      Slot slot;
      double value;
    };
    std::vector<Placed> placed;
    nlohmann::json materials = nlohmann::json::array();
    for (int i = 0; i < count; ++i) {
      const bool draft = *rc::gen::arbitrary<bool>();
      std::vector<Slot> slots = coreSlots();
      const auto sheen = sheenSlots(draft);
      slots.insert(slots.end(), sheen.begin(), sheen.end());
      nlohmann::json m = nlohmann::json::object();
      for (const auto& s : slots) {
        if (!*rc::gen::weightedElement<bool>({{1, false}, {1, true}})) continue;
        nlohmann::json* at = &m;
        for (const auto& k : s.keys) at = &(*at)[k];
        const double value = *inRange(s.range);
        if (s.element >= 0) {
          // Arrays are written whole: a missing element would be a wrong-length error instead.
          const std::size_t length = s.keys.back() == "baseColorFactor" ? 4 : 3;
          if (!at->is_array()) *at = nlohmann::json::array();
          while (at->size() < length) at->push_back(0.25);
          (*at)[std::size_t(s.element)] = value;
        } else {
          *at = value;
        }
        placed.push_back({i, s, value});
      }
      // A draft with none of its keys placed would read as ratified.
      if (draft && !m.contains("extensions")) m["extensions"]["KHR_materials_sheen"]["intensityFactor"] = 1.0;
      if (draft && !m["extensions"].contains("KHR_materials_sheen"))
        m["extensions"]["KHR_materials_sheen"]["intensityFactor"] = 1.0;
      materials.push_back(m);
    }
    // Array elements not placed explicitly hold 0.25; only explicitly placed values are checked.
    const std::string valid = nlohmann::json{{"materials", materials}}.dump();
    const bool corrupt = !placed.empty() && *rc::gen::weightedElement<bool>({{1, false}, {2, true}});
    if (!corrupt) {
      std::vector<MaterialParams> got;
      try {
        got = readMaterials(write("m.json", valid));
      } catch (const Error& e) {
        RC_FAIL(std::string("rejected: ") + e.what());
      }
      RC_ASSERT(got.size() == std::size_t(count));
      for (const auto& p : placed) {
        if (p.slot.keys.back() == "baseColorFactor" && p.slot.element == 3) continue;
        // emissiveFactor above the schema's 1 is clamped with a warning (test_emissive_factor.cpp).
        const float read = float(p.value), have = fieldOf(got[std::size_t(p.material)], p.slot);
        const float want = p.slot.keys.back() == "emissiveFactor" ? std::min(read, 1.0f) : read;
        if (!(have == want))
          RC_FAIL("materials[" + std::to_string(p.material) + "]" + p.slot.path() + ": read " + std::to_string(have) +
                  " for " + num(p.value));
      }
      return;
    }
    // One placed value becomes bad; a sentinel number marks where its text goes.
    const Placed& victim = *rc::gen::elementOf(placed);
    const bool beyondDouble = *rc::gen::weightedElement<bool>({{5, false}, {1, true}});
    const BadJson bad = beyondDouble ? BadJson{"1e999", ""} : *badJson(victim.slot.range);
    nlohmann::json doc = nlohmann::json{{"materials", materials}};
    nlohmann::json* at = &doc["materials"][std::size_t(victim.material)];
    for (const auto& k : victim.slot.keys) at = &(*at)[k];
    if (victim.slot.element >= 0) at = &(*at)[std::size_t(victim.slot.element)];
    *at = 123456789.25;
    std::string text = doc.dump(1);  // one key per line, so the line number below is meaningful
    const auto sentinel = text.find("123456789.25");
    RC_ASSERT(sentinel != std::string::npos);
    text.replace(sentinel, 12, bad.text);
    const std::string path = write("m.json", text);
    std::string got;
    try {
      readMaterials(path);
    } catch (const Error& e) {
      got = e.what();
    }
    if (beyondDouble) {
      const std::string line = std::to_string(1 + std::count(text.begin(), text.begin() + long(sentinel), '\n'));
      RC_ASSERT(got.rfind(path + ": invalid JSON: ", 0) == 0);
      RC_ASSERT(got.find("1e999") != std::string::npos);
      RC_ASSERT(got.find(" at line " + line + "; numbers must be finite") != std::string::npos);
      return;
    }
    const std::string want = path + ": materials[" + std::to_string(victim.material) + "]" + victim.slot.path() +
                             ": expected " + expectedText(victim.slot.range) + ", got " + bad.shown;
    RC_ASSERT(got == want);
  });
}

}  // namespace
