// End-to-end tests of the brdfcl command line: the built binary (BRDFCL_CLI_PATH) is run as a user
// would run it, and its files, exit status and stderr are checked against the eval contract
// (CSV/NPY in and out, --grid, options; the errors and devices: test_cli_errors.cpp).
#include "cli_eval.hpp"

using namespace brdfcl::test::clieval;

namespace {

// 1. Happy path

TEST_F(Cli, CsvMatchesReference) {
  const auto samples = standardSamples();
  const std::string m = write("scene.gltf", kGltf), s = write("s.csv", samplesCsv(samples));
  const RunResult r = eval(m, s, path("o.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_EQ(listWork(), (std::set<std::string>{"scene.gltf", "s.csv", "o.csv"}));

  const CsvResult out = readCsvResult(path("o.csv"));
  ASSERT_EQ(out.values.size(), 3 * samples.size());
  expectMatchesReference(out.values, gltfMaterials(), samples, EvalOptions{});

  std::size_t below = 0, nonZero = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const std::string& t = out.text[3 * i + c];
      if (belowHorizon(samples[i])) {
        EXPECT_EQ(out.values[3 * i + c], 0.0) << "row " << i << " is below the horizon but gives " << t;
      } else {
        EXPECT_GT(out.values[3 * i + c], 0.0) << "row " << i << ": " << t;
        EXPECT_TRUE(hasNineSignificantDigits(t)) << "row " << i << ": '" << t << "' has fewer than 9 digits";
        ++nonZero;
      }
    }
    below += belowHorizon(samples[i]);
  }
  // The fixture must exercise both kinds of rows, or the checks above prove little.
  EXPECT_GE(below, 6u);
  EXPECT_GE(nonZero, 3 * 40u);
}

// 2. NPY in either precision and NPY out give what the CSV run gives.
TEST_F(Cli, NpyInputsAndOutputMatchCsv) {
  const auto samples = standardSamples();
  const std::string m = write("m.json", kGltf);
  const std::string csv = write("s.csv", samplesCsv(samples));
  const std::string f32 = write("s32.npy", samplesNpy(samples, true));
  const std::string f64 = write("s64.NPY", samplesNpy(samples, false));

  RunResult r = eval(m, csv, path("o.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  const auto csvOut = readCsvResult(path("o.csv")).values;
  ASSERT_EQ(csvOut.size(), 3 * samples.size());

  r = eval(m, f64, path("o64.csv"));
  ASSERT_EQ(r.status, 0) << r.describe();
  EXPECT_EQ(readFile(path("o64.csv")), readFile(path("o.csv"))) << "float64 NPY input changes the CSV output";

  const auto fromCsv = evalNpy(m, csv);
  const auto from32 = evalNpy(m, f32);
  const auto from64 = evalNpy(m, f64, {}, "o.NPY");
  expectClose(fromCsv, csvOut, 1e-6, 0.0, "NPY output vs CSV output");
  // The inputs hold identical numbers, so the directions and hence the results are identical.
  EXPECT_EQ(from32, fromCsv);
  EXPECT_EQ(from64, fromCsv);
}

// 3. --grid: every material x every direction, material-major, with or without a material column.
TEST_F(Cli, GridIsMaterialMajorProduct) {
  const auto all = standardSamples();
  const std::vector<Sample> dirs(all.begin(), all.begin() + 14);
  const auto materials = gltfMaterials();
  const std::string m = write("m.json", kGltf);

  std::vector<Sample> expanded;
  for (std::uint32_t k = 0; k < materials.size(); ++k)
    for (const auto& d : dirs) expanded.push_back({k, d.L, d.V});
  const auto perSample = evalNpy(m, write("expanded.csv", samplesCsv(expanded)));
  ASSERT_EQ(perSample.size(), 3 * materials.size() * dirs.size());
  expectMatchesReference(perSample, materials, expanded, EvalOptions{});

  const std::vector<std::pair<std::string, std::string>> inputs = {
      {"g7.csv", samplesCsv(dirs, true)},
      {"g6.csv", samplesCsv(dirs, false)},
      {"g6.npy", samplesNpy(dirs, true, false)},
      {"g7.npy", samplesNpy(dirs, false, true)},
  };
  for (const auto& [name, content] : inputs) {
    SCOPED_TRACE(name);
    const auto grid = evalNpy(m, write(name, content), {"--grid"});
    expectClose(grid, perSample, 1e-6, 1e-30, "--grid vs per-sample evaluation");
  }

  // CSV output of the grid too: the row count is materials x directions.
  const RunResult r = eval(m, path("g6.csv"), path("grid.csv"), {"--grid"});
  ASSERT_EQ(r.status, 0) << r.describe();
  expectClose(readCsvResult(path("grid.csv")).values, perSample, 2e-7, 0.0, "--grid CSV output");
}

// 4. Every option value selects its variant.
TEST_F(Cli, OptionValuesSelectTheirVariant) {
  const auto samples = standardSamples();
  const auto materials = gltfMaterials();
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(samples));

  const auto defaults = evalNpy(m, s);
  const auto explicitDefaults = evalNpy(m, s,
                                        {"--sheen-visibility", "charlie", "--sheen-distribution", "charlie",
                                         "--sheen-scaling", "min", "--lobe", "all"});
  EXPECT_EQ(explicitDefaults, defaults);

  struct Variant {
    std::vector<std::string> args;
    EvalOptions options;
  };
  EvalOptions o;
  std::vector<Variant> variants;
  o = {};
  o.sheenVisibility = SheenVisibility::Ashikhmin;
  variants.push_back({{"--sheen-visibility", "ashikhmin"}, o});
  o = {};
  o.sheenDistribution = SheenDistribution::Ashikhmin;
  variants.push_back({{"--sheen-distribution", "ashikhmin"}, o});
  o = {};
  o.sheenScaling = SheenScaling::View;
  variants.push_back({{"--sheen-scaling", "view"}, o});
  o = {};
  o.sheenScaling = SheenScaling::None;
  variants.push_back({{"--sheen-scaling", "none"}, o});
  const std::pair<const char*, Lobe> lobes[] = {
      {"diffuse", Lobe::Diffuse}, {"specular", Lobe::Specular}, {"sheen", Lobe::Sheen}, {"clearcoat", Lobe::Clearcoat}};
  for (const auto& [name, lobe] : lobes) {
    o = {};
    o.lobe = lobe;
    variants.push_back({{"--lobe", name}, o});
  }

  std::map<std::string, std::vector<double>> results;
  for (const auto& v : variants) {
    const std::string label = v.args[0] + " " + v.args[1];
    SCOPED_TRACE(label);
    results[label] = evalNpy(m, s, v.args);
    expectMatchesReference(results[label], materials, samples, v.options);
  }

  // The lobes partition the sum.
  std::vector<double> sum(defaults.size(), 0.0);
  for (const auto& [name, lobe] : lobes) {
    const auto& part = results[std::string("--lobe ") + name];
    ASSERT_EQ(part.size(), sum.size());
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += part[i];
  }
  expectClose(sum, defaults, 1e-4, 1e-6, "sum of --lobe diffuse/specular/sheen/clearcoat vs all");

  // Facts that hold whatever the formulas, so a wrong option mapping fails even if the reference
  // shared the mistake: the sheen options change the ratified sheen material but not the one
  // without sheen, and only material 1 has a clearcoat lobe.
  const auto differsOn = [&](const std::vector<double>& a, const std::vector<double>& b, std::uint32_t material) {
    for (std::size_t i = 0; i < samples.size(); ++i)
      if (samples[i].material == material && !belowHorizon(samples[i]))
        for (int c = 0; c < 3; ++c)
          if (std::fabs(a[3 * i + c] - b[3 * i + c]) > 1e-4 * std::fabs(b[3 * i + c])) return true;
    return false;
  };
  const auto equalOn = [&](const std::vector<double>& a, const std::vector<double>& b, std::uint32_t material) {
    for (std::size_t i = 0; i < samples.size(); ++i)
      if (samples[i].material == material)
        for (int c = 0; c < 3; ++c)
          if (std::fabs(a[3 * i + c] - b[3 * i + c]) > 1e-6 * std::fabs(b[3 * i + c])) return false;
    return true;
  };
  for (const char* label : {"--sheen-visibility ashikhmin", "--sheen-distribution ashikhmin", "--sheen-scaling view",
                            "--sheen-scaling none"}) {
    SCOPED_TRACE(label);
    EXPECT_TRUE(differsOn(results[label], defaults, 1)) << "no effect on the ratified sheen material";
    EXPECT_TRUE(equalOn(results[label], defaults, 0)) << "changes the material without sheen";
  }
  for (std::uint32_t k : {0u, 2u}) {
    EXPECT_TRUE(equalOn(results["--lobe clearcoat"], std::vector<double>(defaults.size(), 0.0), k));
    EXPECT_TRUE(differsOn(results["--lobe diffuse"], defaults, k));
  }
  EXPECT_TRUE(equalOn(results["--lobe sheen"], std::vector<double>(defaults.size(), 0.0), 0));
  EXPECT_TRUE(differsOn(results["--lobe clearcoat"], std::vector<double>(defaults.size(), 0.0), 1));
}

TEST_F(Cli, UnknownOptionsAndValuesAreUserErrors) {
  const std::string m = write("m.json", kGltf), s = write("s.csv", samplesCsv(standardSamples()));
  const std::string out = path("o.csv");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--lobe", "foo"}, "--lobe"},
      {{"--sheen-scaling", "bar"}, "--sheen-scaling"},
      {{"--sheen-visibility", "velvet"}, "--sheen-visibility"},
      {{"--sheen-distribution", "ggx"}, "--sheen-distribution"},
      {{"--lobe", "Diffuse"}, "--lobe"},  // spellings are exact
      {{"--frobnicate"}, "--frobnicate"},
      {{"--lobe"}, "--lobe"},  // value missing
  };
  for (const auto& [args, needle] : cases) {
    SCOPED_TRACE(args[0] + (args.size() > 1 ? " " + args[1] : ""));
    std::vector<std::string> needles{needle};
    if (args.size() > 1) needles.push_back("'" + args[1] + "'");  // the rejected value too
    expectUserError(eval(m, s, out, args), needles);
    EXPECT_FALSE(fs::exists(out));
  }
  expectUserError(run({"eval", "--materials", m, "--samples", s}), {"--out"});
  expectUserError(run({"frobnicate"}), {"frobnicate"});  // an unknown subcommand
  EXPECT_EQ(listWork(), (std::set<std::string>{"m.json", "s.csv"}));
}

// ---------------------------------------------------------------------------------------------

}  // namespace
