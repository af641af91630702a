// End-to-end tests of the brdfcl command line, continued from test_cli.cpp: bad input is one line
// naming the file and place with nothing left behind, textures warn once, devices are listed and
// chosen, and the binary runs from any folder.
#include "cli_eval.hpp"

using namespace brdfcl::test::clieval;

namespace {

// 5. Bad input: one line naming the file and place, exit 2, no output and no temporaries.

struct BadCase {
  std::string what;
  std::vector<std::pair<std::string, std::string>> files;  // name, content
  std::string materials = "m.json", samples = "s.csv", out = "o.csv";
  std::vector<std::string> extra;
  std::vector<std::string> needles;  // the file name and where in it
};

std::string csvWithRow(const std::string& row, std::size_t at) {
  // `row` becomes file line `at` (the header is line 1) among valid rows.
  std::string t = "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
  for (std::size_t line = 2; line <= 6; ++line) t += line == at ? row + "\n" : "1,0.25,0.5,1,0,0.125,1\n";
  return t;
}

std::string npyWithRow(const std::vector<double>& row, std::size_t at, bool float32) {
  std::vector<double> v;
  for (std::size_t i = 0; i < 4; ++i) {
    const std::vector<double> good{2, 0.25, 0.5, 1, 0, 0.125, 1};
    const auto& r = i == at ? row : good;
    v.insert(v.end(), r.begin(), r.end());
  }
  return brdfcl::test::npyArray(v, 7, float32);
}

std::string gltfWith(const std::string& secondMaterial) {
  return "{\n  \"asset\": {\"version\": \"2.0\"},\n  \"materials\": [\n    {\"name\": \"ok\"},\n    " + secondMaterial +
         "\n  ]\n}\n";
}

// Each bad input eval refuses, with the words its one-line error must hold.
std::vector<BadCase> badInputCases() {
  const double nan = std::nan(""), inf = INFINITY;
  return {
      // Files that cannot be read.
      {"missing materials", {}, "absent.json", "s.csv", "o.csv", {}, {"absent.json", "No such file"}},
      {"materials is a directory", {}, "adir", "s.csv", "o.csv", {}, {"adir"}},
      {"missing samples", {}, "m.json", "absent.csv", "o.csv", {}, {"absent.csv", "No such file"}},
      {"samples is a directory", {}, "m.json", "adir", "o.csv", {}, {"adir"}},
      // Materials JSON.
      {"malformed JSON", {{"broken.json", gltfWith("{\"name\": \"x\",, }")}}, "broken.json", "s.csv", "o.csv", {},
       {"broken.json", "line 5"}},
      {"NaN literal", {{"nan.json", gltfWith("{\"pbrMetallicRoughness\": {\"roughnessFactor\": NaN}}")}}, "nan.json",
       "s.csv", "o.csv", {}, {"nan.json", "line 5"}},
      {"overflowing number",
       {{"inf.json", gltfWith("{\"pbrMetallicRoughness\": {\n      \"roughnessFactor\": 1e999}}")}}, "inf.json",
       "s.csv", "o.csv", {}, {"inf.json", "line 6"}},
      {"wrong type",
       {{"type.json", gltfWith("{\"pbrMetallicRoughness\": {\"metallicFactor\": \"0.5\"}}")}}, "type.json", "s.csv",
       "o.csv", {}, {"type.json", "materials[1].pbrMetallicRoughness.metallicFactor"}},
      {"out of range",
       {{"range.json", gltfWith("{\"extensions\": {\"KHR_materials_clearcoat\": {\"clearcoatFactor\": 1.5}}}")}},
       "range.json", "s.csv", "o.csv", {},
       {"range.json", "materials[1].extensions.KHR_materials_clearcoat.clearcoatFactor"}},
      {"short color",
       {{"color.json", gltfWith("{\"extensions\": {\"KHR_materials_sheen\": {\"sheenColorFactor\": [1, 0]}}}")}},
       "color.json", "s.csv", "o.csv", {}, {"color.json", "sheenColorFactor"}},
      {"materials not an array", {{"obj.json", "{\"materials\": {\"name\": \"x\"}}"}}, "obj.json", "s.csv", "o.csv", {},
       {"obj.json", "materials"}},
      {"no materials", {{"none.json", "{\"asset\": {\"version\": \"2.0\"}}"}}, "none.json", "s.csv", "o.csv", {},
       {"none.json", "materials"}},
      // Samples CSV.
      {"short row", {{"short.csv", csvWithRow("1,0.25,0.5,1,0,0.125", 3)}}, "m.json", "short.csv", "o.csv", {},
       {"short.csv:3:"}},
      {"non-numeric field", {{"text.csv", csvWithRow("1,0.25,abc,1,0,0.125,1", 4)}}, "m.json", "text.csv", "o.csv", {},
       {"text.csv:4:"}},
      {"empty field", {{"empty.csv", csvWithRow("1,0.25,,1,0,0.125,1", 2)}}, "m.json", "empty.csv", "o.csv", {},
       {"empty.csv:2:"}},
      {"NaN field", {{"nan.csv", csvWithRow("1,nan,0.5,1,0,0.125,1", 5)}}, "m.json", "nan.csv", "o.csv", {},
       {"nan.csv:5:"}},
      {"Inf field", {{"inf.csv", csvWithRow("1,0.25,0.5,1,0,0.125,-inf", 6)}}, "m.json", "inf.csv", "o.csv", {},
       {"inf.csv:6:"}},
      {"material index out of range", {{"idx.csv", csvWithRow("3,0.25,0.5,1,0,0.125,1", 3)}}, "m.json", "idx.csv",
       "o.csv", {}, {"idx.csv:3:", "3"}},
      {"negative material index", {{"neg.csv", csvWithRow("-1,0.25,0.5,1,0,0.125,1", 2)}}, "m.json", "neg.csv",
       "o.csv", {}, {"neg.csv:2:"}},
      {"fractional material index", {{"frac.csv", csvWithRow("0.5,0.25,0.5,1,0,0.125,1", 4)}}, "m.json", "frac.csv",
       "o.csv", {}, {"frac.csv:4:"}},
      {"zero-length L", {{"zl.csv", csvWithRow("1,0,0,0,0,0.125,1", 2)}}, "m.json", "zl.csv", "o.csv", {},
       {"zl.csv:2:", "L"}},
      {"zero-length V", {{"zv.csv", csvWithRow("1,0.25,0.5,1,0,-0,0", 6)}}, "m.json", "zv.csv", "o.csv", {},
       {"zv.csv:6:", "V"}},
      {"header only", {{"hdr.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n"}}, "m.json", "hdr.csv", "o.csv", {}, {"hdr.csv"}},
      {"empty file", {{"nothing.csv", ""}}, "m.json", "nothing.csv", "o.csv", {}, {"nothing.csv"}},
      {"missing header", {{"nohdr.csv", "1,0.25,0.5,1,0,0.125,1\n"}}, "m.json", "nohdr.csv", "o.csv", {},
       {"nohdr.csv:1:"}},
      {"no material column without --grid", {{"six.csv", "Lx,Ly,Lz,Vx,Vy,Vz\n0.25,0.5,1,0,0.125,1\n"}}, "m.json",
       "six.csv", "o.csv", {}, {"six.csv: header: missing column material", "--grid"}},
      // Samples NPY (rows are 0-based, as numpy indexes them).
      {"NPY NaN", {{"nan.npy", npyWithRow({0, 0.25, nan, 1, 0, 0.125, 1}, 2, true)}}, "m.json", "nan.npy", "o.csv", {},
       {"nan.npy", "row 2"}},
      {"NPY Inf", {{"inf.npy", npyWithRow({0, 0.25, 0.5, 1, inf, 0.125, 1}, 3, false)}}, "m.json", "inf.npy", "o.csv",
       {}, {"inf.npy", "row 3"}},
      {"NPY material index out of range", {{"idx.npy", npyWithRow({7, 0.25, 0.5, 1, 0, 0.125, 1}, 1, false)}}, "m.json",
       "idx.npy", "o.csv", {}, {"idx.npy", "row 1"}},
      {"NPY zero-length V", {{"zv.npy", npyWithRow({0, 0.25, 0.5, 1, 0, 0, 0}, 0, true)}}, "m.json", "zv.npy", "o.csv",
       {}, {"zv.npy", "row 0"}},
      {"NPY wrong shape", {{"shape.npy", brdfcl::test::npyArray(std::vector<double>(10, 0.5), 5, true)}}, "m.json", "shape.npy", "o.csv",
       {}, {"shape.npy", "shape"}},
      {"NPY (N,6) without --grid", {{"six.npy", brdfcl::test::npyArray(std::vector<double>(12, 0.5), 6, true)}}, "m.json", "six.npy",
       "o.csv", {}, {"six.npy", "shape"}},
      {"NPY truncated", {{"cut.npy", npyWithRow({0, 0.25, 0.5, 1, 0, 0.125, 1}, 0, false).substr(0, 200)}}, "m.json",
       "cut.npy", "o.csv", {}, {"cut.npy"}},
      {"not an NPY file", {{"csv.npy", "material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n"}}, "m.json", "csv.npy", "o.csv",
       {}, {"csv.npy"}},
      // The output side and the options, with otherwise good input.
      {"output directory missing", {}, "m.json", "s.csv", "nodir/o.csv", {}, {"nodir/o.csv"}},
      {"unknown lobe", {}, "m.json", "s.csv", "o.csv", {"--lobe", "foo"}, {"--lobe", "foo"}},
      {"unknown option", {}, "m.json", "s.csv", "o.npy", {"--frobnicate"}, {"--frobnicate"}},
      {"bad device index", {}, "m.json", "s.csv", "o.csv", {"--device", "99"}, {"99"}},
      {"no device of that name", {}, "m.json", "s.csv", "o.npy", {"--device", "no-such"}, {"no-such"}},
  };
}

TEST_F(Cli, BadInputIsOneLineErrorAndLeavesNoOutput) {
  std::vector<BadCase> cases = badInputCases();
  // Root reads any file whatever its mode, so the permission case only means something otherwise.
  if (::geteuid() != 0)
    cases.push_back({"unreadable materials", {{"secret.json", kGltf}}, "secret.json", "s.csv", "o.csv", {},
                     {"secret.json", "Permission denied"}});

  for (std::size_t k = 0; k < cases.size(); ++k) {
    const BadCase& c = cases[k];
    SCOPED_TRACE(c.what);
    const fs::path dir = work_ / ("case" + std::to_string(k));
    fs::create_directories(dir / "adir");
    writeFile(dir / "m.json", kGltf);
    writeFile(dir / "s.csv", samplesCsv(standardSamples()));
    for (const auto& [name, content] : c.files) writeFile(dir / name, content);
    if (c.what == "unreadable materials") fs::permissions(dir / "secret.json", fs::perms::none);
    std::vector<std::string> args{"eval", "--materials", (dir / c.materials).string(), "--samples",
                                  (dir / c.samples).string(), "--out", (dir / c.out).string()};
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const auto listing = [&] {
      std::set<std::string> names;
      for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
      return names;
    };

    const auto before = listing();
    expectUserError(run(args), c.needles);
    EXPECT_EQ(listing(), before) << "the failed run left files behind";

    // A result from an earlier run must survive a failed one.
    if (fs::exists(dir / c.out) || !fs::exists((dir / c.out).parent_path())) continue;
    writeFile(dir / c.out, "keep me");
    const auto withOld = listing();
    expectUserError(run(args), c.needles);
    EXPECT_EQ(readFile(dir / c.out), "keep me");
    EXPECT_EQ(listing(), withOld) << "the failed run left files behind";
  }
}

TEST_F(Cli, OutputPathThatIsADirectoryIsAUserError) {
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(standardSamples()));
  fs::create_directories(work_ / "out.csv");
  const auto before = listWork();
  expectUserError(eval(m, s, path("out.csv")), {"out.csv"});
  EXPECT_EQ(listWork(), before);
}

// ---------------------------------------------------------------------------------------------
// 6. Textures are ignored with one warning per material.

TEST_F(Cli, TextureReferencesWarnOncePerMaterial) {
  const std::string textured = R"({
  "asset": {"version": "2.0"},
  "materials": [
    {"name": "plain", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.35, 0.1, 1.0], "metallicFactor": 0.0,
                                               "roughnessFactor": 0.45}},
    {"name": "Velvet Sofa",
     "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.5, 0.7, 0.5], "metallicFactor": 0.25, "roughnessFactor": 0.6,
                              "baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1}},
     "extensions": {
       "KHR_materials_sheen": {"sheenColorFactor": [0.6, 0.4, 0.5], "sheenRoughnessFactor": 0.35,
                               "sheenColorTexture": {"index": 2}},
       "KHR_materials_clearcoat": {"clearcoatFactor": 0.7, "clearcoatRoughnessFactor": 0.2},
       "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 0.9}}},
    {"normalTexture": {"index": 3},
     "pbrMetallicRoughness": {"metallicFactor": 0.1, "roughnessFactor": 0.55},
     "extensions": {"KHR_materials_sheen": {"intensityFactor": 0.8}}}
  ]
})";
  const auto samples = standardSamples();
  const std::string s = write("s.csv", samplesCsv(samples));
  const RunResult r = eval(write("tex.gltf", textured), s, path("o.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.errorLines().empty()) << r.describe();
  const auto warnings = r.warningLines();
  ASSERT_EQ(warnings.size(), 2u) << r.describe();
  EXPECT_NE(warnings[0].find("Velvet Sofa"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("baseColorTexture"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("materials[2]"), std::string::npos) << warnings[1];

  // Factors only: the same numbers as the texture-free document.
  const RunResult plain = eval(write("m.json", kGltf), s, path("plain.csv"));
  ASSERT_EQ(plain.status, 0) << plain.describe();
  EXPECT_EQ(readFile(path("o.csv")), readFile(path("plain.csv")));
}

// A JSON object that is not glTF is fine as long as it has a materials array.
TEST_F(Cli, AcceptsPlainMaterialsObject) {
  const auto samples = standardSamples();
  const std::string doc = R"({"materials": [{}, {"pbrMetallicRoughness": {"metallicFactor": 0.0}}, {}], "other": 1})";
  const RunResult r = eval(write("mats.json", doc), write("s.csv", samplesCsv(samples)), path("o.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  std::vector<MaterialParams> materials(3);  // the spec defaults: white, metallic 1, roughness 1
  materials[1].metallic = 0.0f;
  expectMatchesReference(readCsvResult(path("o.csv")).values, materials, samples, EvalOptions{});
}

// ---------------------------------------------------------------------------------------------
// 7. Devices

TEST_F(Cli, DevicesListAndSelection) {
  const RunResult list = run({"devices"});
  ASSERT_EQ(list.status, 0) << list.describe();
  EXPECT_TRUE(list.err.empty()) << list.err;
  std::smatch match;
  ASSERT_TRUE(std::regex_search(list.out, match, std::regex(R"((^|\n)\[0\] ([^\n]+))"))) << list.out;
  const std::string name = match[2];

  const auto samples = standardSamples();
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(samples));
  const auto byDefault = evalNpy(m, s);
  EXPECT_EQ(evalNpy(m, s, {"--device", "0"}), byDefault);
  EXPECT_EQ(evalNpy(m, s, {"--device", name.substr(0, std::min<std::size_t>(name.size(), 8))}), byDefault)
      << "selecting '" << name << "' by a name prefix";

  for (const char* bad : {"99", "no-such"}) {
    SCOPED_TRACE(bad);
    expectUserError(eval(m, s, path("o.csv"), {"--device", bad}), {bad});
    EXPECT_FALSE(fs::exists(path("o.csv")));
  }
}

// An index too large for any integer type is still a bad index, not an internal fault.
TEST_F(Cli, HugeDeviceIndexIsAUserError) {
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(standardSamples()));
  expectUserError(eval(m, s, path("o.csv"), {"--device", "99999999999999999999999"}), {"99999999999999999999999"});
  EXPECT_FALSE(fs::exists(path("o.csv")));
}

// ---------------------------------------------------------------------------------------------
// 8. Kernels are embedded: the tool runs from any directory, with paths relative to it.

TEST_F(Cli, RunsFromAnotherDirectoryWithRelativePaths) {
  const auto samples = standardSamples();
  write("m.json", kGltf);
  write("s.npy", samplesNpy(samples, true));
  fs::create_directories(work_ / "results");
  const RunResult r = run({"eval", "--materials", "m.json", "--samples", "s.npy", "--out", "results/o.csv"},
                          work_.string());
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.err.empty()) << r.err;
  const auto out = readCsvResult(work_ / "results" / "o.csv");
  expectMatchesReference(out.values, gltfMaterials(), samples, EvalOptions{});
  EXPECT_EQ(listWork(), (std::set<std::string>{"m.json", "s.npy", "results", "results/o.csv"}));
}

}  // namespace
