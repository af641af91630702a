// `brdfcl eval --chunk`: the files are byte-identical to a one-shot run's whatever the chunk, a bad
// row late in the file leaves no output, and 100M samples evaluate in under 1 GiB resident.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "npy.hpp"
#include "process.hpp"
#include "stream_files.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

const char* kMaterialsJson = R"({"materials": [
  {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.35, 0.1, 1], "metallicFactor": 0, "roughnessFactor": 0.45}},
  {"pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.5, 0.7, 1], "metallicFactor": 0.25, "roughnessFactor": 0.6},
   "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [0.6, 0.4, 0.5], "sheenRoughnessFactor": 0.35},
                  "KHR_materials_clearcoat": {"clearcoatFactor": 0.7, "clearcoatRoughnessFactor": 0.2},
                  "KHR_materials_anisotropy": {"anisotropyStrength": 0.6, "anisotropyRotation": 0.9}}},
  {"pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0.2}}
]})";

RunResult eval(const ScratchDir& dir, const std::vector<std::string>& args) {
  std::vector<std::string> argv{BRDFCL_CLI_PATH, "eval"};
  argv.insert(argv.end(), args.begin(), args.end());
  return runProcess(argv, dir.dir());
}

TEST(StreamCli, ChunkOptionGivesIdenticalFiles) {
  ScratchDir dir("stream-cli");
  writeFile(dir.path("m.json"), kMaterialsJson);
  const auto rows = randomRows(2000, true, 3, 14);
  writeFile(dir.path("s.csv"), csvFile(rows, true));
  writeFile(dir.path("s.npy"), npyFile(rows, 7, true, true));
  writeFile(dir.path("d.npy"), npyFile(randomRows(700, false, 1, 15), 6, true, false));
  struct Case {
    std::string in, out;
    std::vector<std::string> extra;
  };
  for (const Case& c : {Case{"s.csv", ".csv", {}}, Case{"s.npy", ".npy", {}}, Case{"s.npy", ".csv", {"--lobe", "sheen"}},
                        Case{"d.npy", ".npy", {"--grid"}}}) {
    std::string reference;
    for (const std::string chunk : {"", "1000000", "2000", "333", "5"}) {
      std::vector<std::string> args{"--materials", dir.path("m.json"), "--samples", dir.path(c.in), "--out",
                                    dir.path("o" + c.out)};
      args.insert(args.end(), c.extra.begin(), c.extra.end());
      if (!chunk.empty()) args.insert(args.end(), {"--chunk", chunk});
      const RunResult r = eval(dir, args);
      ASSERT_EQ(r.status, 0) << r.describe();
      const std::string got = slurp(dir.path("o" + c.out));
      if (chunk.empty())
        reference = got;
      else
        EXPECT_EQ(got, reference) << c.in << " -> " << c.out << " --chunk " << chunk;
    }
  }
}

TEST(StreamCli, ABadRowLateInTheFileLeavesNoOutput) {
  ScratchDir dir("stream-cli");
  writeFile(dir.path("m.json"), kMaterialsJson);
  std::string csv = csvFile(randomRows(5000, true, 3, 16), true);
  csv += "1,0,0,1,0,0,inf\n";  // line 5002
  writeFile(dir.path("s.csv"), csv);
  writeFile(dir.path("o.npy"), "previous results");
  const RunResult r = eval(dir, {"--materials", dir.path("m.json"), "--samples", dir.path("s.csv"), "--out",
                                 dir.path("o.npy"), "--chunk", "100"});
  EXPECT_EQ(r.status, 2) << r.describe();
  EXPECT_EQ(r.errorLines(), std::vector<std::string>{"brdfcl: " + dir.path("s.csv") +
                                                     ":5002: field 'Vz' is not finite: 'inf'"});
  EXPECT_EQ(slurp(dir.path("o.npy")), "previous results");
  EXPECT_EQ(dir.list(), (std::vector<std::string>{"m.json", "o.npy", "s.csv", "stderr", "stdout"}));
}

TEST(StreamCli, ChunkOutOfRange) {
  ScratchDir dir("stream-cli");
  writeFile(dir.path("m.json"), kMaterialsJson);
  writeFile(dir.path("s.csv"), csvFile(randomRows(3, true, 3, 17), true));
  for (const std::string v : {"0", "-5", "268435457"}) {
    const RunResult r = eval(dir, {"--materials", dir.path("m.json"), "--samples", dir.path("s.csv"), "--out",
                                   dir.path("o.csv"), "--chunk", v});
    EXPECT_EQ(r.status, 2) << r.describe();
    EXPECT_EQ(r.errorLines(),
              std::vector<std::string>{"brdfcl: --chunk " + v + " is out of range; use 1 to 268435456"});
  }
  EXPECT_EQ(dir.list(), (std::vector<std::string>{"m.json", "s.csv", "stderr", "stdout"}));
}

// The bound: a 100M-sample NPY file (2.8 GB of float32) evaluates with under 1 GiB
// resident. BRDFCL_STREAM_SAMPLES overrides the count. Sanitizer builds check 10M samples for
// correctness only: their shadow memory and quarantine are not the tool's own. Rows repeat a block of random samples, so a
// spot check of rows anywhere in the output can be computed from the block.
TEST(StreamCli, HundredMillionSamplesStayUnderOneGiB) {
  std::size_t n = kAddressSanitizer ? 10'000'000 : 100'000'000;
  if (const char* e = std::getenv("BRDFCL_STREAM_SAMPLES")) n = std::strtoull(e, nullptr, 10);
  ScratchDir dir("stream-big");
  writeFile(dir.path("m.json"), kMaterialsJson);
  constexpr std::size_t kBlock = 1 << 16;
  const auto block = randomRows(kBlock, true, 3, 18);
  std::vector<float> blockData(block.begin(), block.end());
  {
    const std::string h = npyHeader(n, 7, true, false);
    std::ofstream out(dir.path("big.npy"), std::ios::binary);
    out.write(h.data(), static_cast<std::streamsize>(h.size()));
    for (std::size_t done = 0; done < n; done += kBlock) {
      const std::size_t rows = std::min(kBlock, n - done);
      out.write(reinterpret_cast<const char*>(blockData.data()), static_cast<std::streamsize>(rows * 7 * 4));
    }
    ASSERT_TRUE(out.good()) << "writing the input file";
  }
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> argv{BRDFCL_CLI_PATH,    "eval",  "--materials", dir.path("m.json"), "--samples",
                                dir.path("big.npy"), "--out", dir.path("out.npy")};
  const RunResult r = runProcess(argv, dir.dir(), "", std::chrono::seconds(900));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.status, 0) << r.describe();
  std::printf("[ stream   ] %zu samples in %.1f s, peak resident %.0f MiB\n", n, seconds, r.maxRssKiB / 1024.0);
  if (!kAddressSanitizer)  // ASan's shadow memory and quarantine alone reach ~1 GiB here
    EXPECT_LT(r.maxRssKiB, 1024 * 1024) << "peak resident set of `brdfcl eval` on " << n << " samples";

  struct stat st {};
  ASSERT_EQ(::stat(dir.path("out.npy").c_str(), &st), 0);
  EXPECT_EQ(static_cast<std::size_t>(st.st_size), 128 + 12 * n);
  std::ifstream out(dir.path("out.npy"), std::ios::binary);
  std::string head(128, '\0');
  out.read(head.data(), 128);
  EXPECT_NE(head.find("'shape': (" + std::to_string(n) + ", 3)"), std::string::npos) << head;

  // Spot check: rows spread over the whole file against the library on the block's samples.
  Samples blockSamples;
  for (std::size_t i = 0; i < kBlock; ++i) {
    blockSamples.material.push_back(static_cast<std::uint32_t>(blockData[7 * i]));
    for (int k = 0; k < 3; ++k) {
      blockSamples.L.push_back(blockData[7 * i + 1 + k]);
      blockSamples.V.push_back(blockData[7 * i + 4 + k]);
    }
  }
  // The reader normalizes; the library expects unit vectors, so go through the same reader.
  writeFile(dir.path("block.npy"), npyFile(block, 7, true, false));
  const auto materials = readMaterials(dir.path("m.json"));
  Evaluator ev(runtime(), EvalOptions{});
  const auto expected = ev.evaluate(materials, readSamples(dir.path("block.npy"), materials.size(), false));
  std::mt19937_64 rng(seed() + 19);
  std::uniform_int_distribution<std::size_t> pick(0, n - 1);
  for (int k = 0; k < 2000; ++k) {
    const std::size_t row = k == 0 ? n - 1 : pick(rng);
    float got[3];
    out.seekg(static_cast<std::streamoff>(128 + 12 * row));
    out.read(reinterpret_cast<char*>(got), 12);
    const std::size_t b = row % kBlock;
    ASSERT_EQ(std::memcmp(got, &expected[3 * b], 12), 0) << "row " << row;
  }
}

}  // namespace
