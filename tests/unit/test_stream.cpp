// Streaming: SampleStream reads any file in chunks with readSamples's exact rows and messages,
// ResultWriter writes chunks byte-identical to writeResults, and evaluateStream gives a one-shot
// run's bytes (`brdfcl eval --chunk`: test_stream_cli.cpp).
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
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <thread>
#include <vector>

#include "brdfcl/stream.hpp"
#include "npy.hpp"
#include "process.hpp"
#include "stream_files.hpp"
#include "support.hpp"

using namespace brdfcl;
using namespace brdfcl::test;

namespace {

// Every chunk of `stream` appended together.
Samples readAllChunks(SampleStream& stream, std::size_t chunk, std::size_t* chunks = nullptr) {
  Samples all, part;
  std::size_t n = 0;
  while (stream.next(chunk, part)) {
    EXPECT_GE(part.size(), 1u);
    EXPECT_LE(part.size(), chunk);
    all.material.insert(all.material.end(), part.material.begin(), part.material.end());
    all.L.insert(all.L.end(), part.L.begin(), part.L.end());
    all.V.insert(all.V.end(), part.V.begin(), part.V.end());
    ++n;
  }
  EXPECT_EQ(part.size(), 0u) << "next() returning false must leave the chunk empty";
  if (chunks) *chunks = n;
  return all;
}

void expectSameSamples(const Samples& a, const Samples& b, const std::string& what) {
  EXPECT_EQ(a.material, b.material) << what;
  // Bitwise: the chunked reader must normalize exactly as the whole-file one.
  EXPECT_TRUE(a.L.size() == b.L.size() && std::memcmp(a.L.data(), b.L.data(), a.L.size() * 4) == 0) << what;
  EXPECT_TRUE(a.V.size() == b.V.size() && std::memcmp(a.V.data(), b.V.data(), a.V.size() * 4) == 0) << what;
}

const std::size_t kChunks[] = {1, 2, 7, 64, 999, 1000, 1001, 100000};

// ---------------------------------------------------------------------------------------------
// SampleStream

TEST(SampleStream, ChunksConcatenateToTheWholeFileRead) {
  ScratchDir dir("stream");
  const std::size_t n = 1000;
  struct Case {
    std::string name, content;
    bool optional;
  };
  const auto withM = randomRows(n, true, 5, 1), without = randomRows(n, false, 1, 2);
  const std::vector<Case> cases = {
      {"m.csv", csvFile(withM, true), false},
      {"crlf.csv", csvFile(withM, true, "\r\n"), false},
      {"open-end.csv", csvFile(withM, true, "\n", false), false},
      {"bom-trailing-blanks.csv", "\xEF\xBB\xBF" + csvFile(withM, true) + "\n  \n\t\n\n", false},
      {"dirs.csv", csvFile(without, false), true},
      {"c32.npy", npyFile(withM, 7, true, false), false},
      {"c64.npy", npyFile(withM, 7, false, false), false},
      {"f32.npy", npyFile(withM, 7, true, true), false},
      {"f64-dirs.npy", npyFile(without, 6, false, true), true},
  };
  for (const auto& c : cases) {
    const std::string p = dir.path(c.name);
    writeFile(p, c.content);
    const Samples whole = readSamples(p, 5, c.optional);
    ASSERT_EQ(whole.size(), n) << c.name;
    for (std::size_t chunk : kChunks) {
      SampleStream stream(p, 5, c.optional);
      EXPECT_EQ(stream.hasMaterialColumn(), c.name.find("dirs") == std::string::npos) << c.name;
      std::size_t chunks = 0;
      expectSameSamples(readAllChunks(stream, chunk, &chunks), whole, c.name + " chunk " + std::to_string(chunk));
      EXPECT_EQ(chunks, (n + chunk - 1) / chunk) << c.name << " chunk " << chunk;
    }
  }
}

TEST(SampleStream, RewindStartsAgainFromTheFirstRow) {
  ScratchDir dir("stream");
  const auto rows = randomRows(300, true, 3, 3);
  for (const std::string name : {"r.csv", "r.npy"}) {
    const std::string p = dir.path(name);
    writeFile(p, name == "r.csv" ? csvFile(rows, true) : npyFile(rows, 7, true, false));
    SampleStream stream(p, 3, false);
    Samples part;
    ASSERT_TRUE(stream.next(100, part));
    stream.rewind();
    const Samples again = readAllChunks(stream, 64);
    stream.rewind();
    expectSameSamples(readAllChunks(stream, 1000), again, name);
    expectSameSamples(again, readSamples(p, 3, false), name);
  }
}

// A bad row found in chunk k is reported with its file line (CSV) or row (NPY), as readSamples
// reports it: the streamed run must name the same place whatever the chunk size.
TEST(SampleStream, ErrorsNameTheSameLineAsTheWholeFileRead) {
  ScratchDir dir("stream");
  const auto rows = randomRows(600, true, 4, 4);
  std::string good = csvFile(rows, true);
  std::vector<std::string> lines;
  {
    std::istringstream in(good);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
  }
  const auto join = [](const std::vector<std::string>& ls) {
    std::string s;
    for (const auto& l : ls) s += l + "\n";
    return s;
  };
  struct Case {
    std::string name;
    std::vector<std::string> lines;
  };
  std::vector<Case> cases;
  auto edited = [&](std::size_t line, const std::string& text) {  // 1-based file line
    auto ls = lines;
    ls[line - 1] = text;
    return ls;
  };
  cases.push_back({"nan.csv", edited(450, "1,nan,0,1,0,0,1")});
  cases.push_back({"word.csv", edited(2, "1,x,0,1,0,0,1")});
  cases.push_back({"short.csv", edited(601, "1,0,0,1")});
  cases.push_back({"index.csv", edited(300, "4,0,0,1,0,0,1")});
  cases.push_back({"zero.csv", edited(123, "1,0,0,0,0,0,1")});
  // Blank lines followed by data, at every position relative to a chunk boundary.
  for (std::size_t at : {2, 3, 8, 9, 10, 101, 102, 600}) {
    auto ls = lines;
    ls.insert(ls.begin() + static_cast<std::ptrdiff_t>(at - 1), {"", "  "});
    cases.push_back({"blank-" + std::to_string(at) + ".csv", ls});
  }
  for (const auto& c : cases) {
    const std::string p = dir.path(c.name);
    writeFile(p, join(c.lines));
    const std::string expected = errorOf([&] { readSamples(p, 4, false); });
    ASSERT_FALSE(expected.empty()) << c.name << " must be rejected";
    for (std::size_t chunk : {1, 7, 8, 9, 100, 101, 599, 600, 601, 5000}) {
      const std::string got = errorOf([&] {
        SampleStream stream(p, 4, false);
        readAllChunks(stream, chunk);
      });
      EXPECT_EQ(got, expected) << c.name << " chunk " << chunk;
    }
  }
  // NPY rows: NaN at row 517 and an out-of-range index at row 3.
  auto nanRows = rows;
  nanRows[517 * 7 + 5] = std::nan("");
  auto badIndex = rows;
  badIndex[3 * 7] = 9;
  for (const auto& [name, values] : {std::pair{std::string("nan.npy"), nanRows}, {"index.npy", badIndex}}) {
    for (bool fortran : {false, true}) {
      const std::string p = dir.path(name);
      writeFile(p, npyFile(values, 7, true, fortran));
      const std::string expected = errorOf([&] { readSamples(p, 4, false); });
      ASSERT_FALSE(expected.empty());
      for (std::size_t chunk : {1, 100, 517, 518, 1000}) {
        const std::string got = errorOf([&] {
          SampleStream stream(p, 4, false);
          readAllChunks(stream, chunk);
        });
        EXPECT_EQ(got, expected) << name << " fortran " << fortran << " chunk " << chunk;
      }
    }
  }
}

// Found by fuzz_samples_csv (tests/fuzz/corpus/samples_csv/stray_cr_in_blank_lines.csv): a line
// "\r\t" is not blank (only a '\r' right before the '\n' is dropped), and the look-ahead over
// the lines after a blank one must use the same rule, or the first error depends on the chunk.
TEST(SampleStream, AStrayCarriageReturnMakesALineNonBlankWhateverTheChunk) {
  ScratchDir dir("stream");
  const std::string p = dir.path("cr.csv");
  writeFile(p, "Lx,Ly,Lz,Vx,Vy,Vz\n\n\t\n\n\n\n\r\n\r\t\n\n\r\t\n\n,\n");
  const std::string expected = p + ":2: empty line; expected 6 fields (Lx,Ly,Lz,Vx,Vy,Vz)";
  EXPECT_EQ(errorOf([&] { readSamples(p, 0, true); }), expected);
  for (std::size_t chunk : {1, 2, 3, 5, 100}) {
    EXPECT_EQ(errorOf([&] {
                SampleStream stream(p, 0, true);
                readAllChunks(stream, chunk);
              }),
              expected)
        << "chunk " << chunk;
  }
  // Blank lines with CRLF ends and then only a "\r" at the end of the file stay trailing blanks.
  writeFile(p, csvFile(randomRows(3, false, 1, 22), false) + "\r\n \r\n\r");
  for (std::size_t chunk : {1, 2, 100}) {
    SampleStream stream(p, 0, true);
    EXPECT_EQ(readAllChunks(stream, chunk).size(), 3u) << chunk;
  }
}

TEST(SampleStream, TrailingBlankLinesAcrossChunksAreNotRows) {
  ScratchDir dir("stream");
  const auto rows = randomRows(10, true, 2, 5);
  const std::string p = dir.path("t.csv");
  writeFile(p, csvFile(rows, true) + std::string(25, '\n') + "   \n\r\n");
  for (std::size_t chunk : {1, 3, 10, 11, 12, 40}) {
    SampleStream stream(p, 2, false);
    EXPECT_EQ(readAllChunks(stream, chunk).size(), 10u) << chunk;
  }
  const std::string empty = dir.path("e.csv");
  writeFile(empty, "material,Lx,Ly,Lz,Vx,Vy,Vz\n\n\n");
  EXPECT_EQ(errorOf([&] {
              SampleStream stream(empty, 2, false);
              readAllChunks(stream, 1);
            }),
            empty + ": no samples (the file has a header but no rows)");
}

// The header is checked when the stream opens; a file cut short afterwards (another process
// rewriting it) must fail cleanly, not read garbage.
TEST(SampleStream, AFileCutShortWhileStreamingIsAnError) {
  ScratchDir dir("stream");
  const std::string p = dir.path("cut.npy");
  writeFile(p, npyFile(randomRows(1000, true, 2, 21), 7, true, false));
  SampleStream stream(p, 2, false);
  Samples part;
  ASSERT_TRUE(stream.next(400, part));
  ASSERT_EQ(::truncate(p.c_str(), 128 + 28 * 500), 0);
  EXPECT_EQ(errorOf([&] { stream.next(400, part); }),
            p + ": truncated while reading (was the file changed during the run?)");
}

// Pipes cannot seek: the stream reads them whole first, for NPY (Fortran order needs it) and CSV.
TEST(SampleStream, ReadsFromAPipe) {
  ScratchDir dir("stream");
  const auto rows = randomRows(500, true, 3, 6);
  for (const std::string name : {"fifo.csv", "fifo.npy"}) {
    const std::string content = name == "fifo.csv" ? csvFile(rows, true) : npyFile(rows, 7, false, true);
    const std::string plain = dir.path("plain-" + name), fifo = dir.path(name);
    writeFile(plain, content);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] { writeFile(fifo, content); });
    Samples got;
    try {
      SampleStream stream(fifo, 3, false);
      got = readAllChunks(stream, 77);
    } catch (...) {
      writer.join();
      throw;
    }
    writer.join();
    expectSameSamples(got, readSamples(plain, 3, false), name);
  }
}

// ---------------------------------------------------------------------------------------------
// ResultWriter

TEST(ResultWriter, ChunksAreByteIdenticalToWriteResults) {
  ScratchDir dir("results");
  std::mt19937_64 rng(seed() + 7);
  std::uniform_real_distribution<float> u(0.0f, 50.0f);
  for (std::size_t n : {0, 1, 5, 1000, 70000}) {
    std::vector<float> rgb(3 * n);
    for (auto& v : rgb) v = u(rng);
    if (n > 2) rgb[4] = 0.0f, rgb[5] = 1e-38f;
    for (const std::string ext : {".csv", ".npy"}) {
      const std::string whole = dir.path("whole" + ext), chunked = dir.path("chunked" + ext);
      writeResults(whole, rgb);
      for (std::size_t chunk : {1, 3, 4096, 100000}) {
        ResultWriter w(chunked);
        for (std::size_t first = 0; first < n; first += chunk)
          w.append(rgb.data() + 3 * first, std::min(chunk, n - first));
        EXPECT_EQ(w.rows(), n);
        w.commit();
        EXPECT_EQ(slurp(chunked), slurp(whole)) << n << " rows, chunk " << chunk << ext;
      }
    }
  }
  const std::string npy = slurp(dir.path("whole.npy"));
  EXPECT_EQ(npy.size(), 128u + 70000u * 12u);
  EXPECT_NE(npy.find("'shape': (70000, 3)"), std::string::npos) << npy.substr(0, 128);
}

TEST(ResultWriter, WithoutCommitLeavesNothingAndKeepsTheOldFile) {
  ScratchDir dir("results");
  const std::string p = dir.path("o.npy");
  writeFile(p, "previous results");
  {
    ResultWriter w(p);
    const float rgb[6] = {1, 2, 3, 4, 5, 6};
    w.append(rgb, 2);
    EXPECT_EQ(dir.list().size(), 2u) << "the temporary sits beside the output while writing";
  }
  EXPECT_EQ(dir.list(), std::vector<std::string>{"o.npy"});
  EXPECT_EQ(slurp(p), "previous results");
  EXPECT_EQ(errorOf([&] { ResultWriter w(dir.path("missing/o.csv")); }),
            "cannot write '" + dir.path("missing/o.csv") + "': No such file or directory");
}

// ---------------------------------------------------------------------------------------------
// evaluateStream: chunked runs give the one-shot bytes

std::vector<MaterialParams> someMaterials(std::size_t n, std::uint64_t salt) {
  std::mt19937_64 rng(seed() + salt);
  std::vector<MaterialParams> m;
  for (std::size_t i = 0; i < n; ++i) m.push_back(randomMaterial(rng));
  return m;
}

std::string streamToFile(Evaluator& ev, const std::vector<MaterialParams>& materials, const std::string& in,
                         const std::string& out, std::size_t chunk, bool grid, StreamStats* stats = nullptr,
                         bool overlap = true) {
  SampleStream samples(in, grid ? 0 : materials.size(), grid);
  ResultWriter writer(out);
  StreamOptions o;
  o.chunk = chunk;
  o.grid = grid;
  o.overlap = overlap;
  const StreamStats s = evaluateStream(ev, materials, samples, writer, o);
  if (stats) *stats = s;
  writer.commit();
  return slurp(out);
}

TEST(Stream, ChunkedEvaluationEqualsOneShot) {
  ScratchDir dir("stream");
  const auto materials = someMaterials(6, 8);
  const auto rows = randomRows(3000, true, 6, 9);
  Evaluator ev(runtime(), EvalOptions{});
  for (const std::string name : {"s.csv", "s.npy"}) {
    const std::string in = dir.path(name), ext = name.substr(1);
    writeFile(in, name == "s.csv" ? csvFile(rows, true) : npyFile(rows, 7, true, false));
    writeResults(dir.path("one-shot" + ext), ev.evaluate(materials, readSamples(in, materials.size(), false)));
    const std::string expected = slurp(dir.path("one-shot" + ext));
    for (std::size_t chunk : {7, 16, 1000, 3000, 1 << 20}) {
      StreamStats stats;
      EXPECT_EQ(streamToFile(ev, materials, in, dir.path("streamed" + ext), chunk, false, &stats), expected)
          << name << " chunk " << chunk;
      EXPECT_EQ(stats.samples, 3000u);
      EXPECT_EQ(stats.rows, 3000u);
      EXPECT_EQ(stats.chunks, (3000 + chunk - 1) / chunk);
      EXPECT_EQ(streamToFile(ev, materials, in, dir.path("serial" + ext), chunk, false, nullptr, false), expected)
          << name << " chunk " << chunk << " without overlap";
    }
  }
  // Large launches run in fixed work-groups, small ones in the runtime's: same bits either way.
  const auto many = randomRows(150000, true, 6, 20);
  const std::string big = dir.path("big.npy");
  writeFile(big, npyFile(many, 7, true, false));
  writeResults(dir.path("big-one.npy"), ev.evaluate(materials, readSamples(big, materials.size(), false)));
  for (std::size_t chunk : {100000, 7777})
    EXPECT_EQ(streamToFile(ev, materials, big, dir.path("big-streamed.npy"), chunk, false),
              slurp(dir.path("big-one.npy")))
        << "chunk " << chunk;
  // One sample per chunk, on a short file: every launch is a partial group of lanes.
  const std::string tiny = dir.path("tiny.npy");
  const auto tinyRows = std::vector<double>(rows.begin(), rows.begin() + 7 * 40);
  writeFile(tiny, npyFile(tinyRows, 7, true, false));
  writeResults(dir.path("tiny-one.npy"), ev.evaluate(materials, readSamples(tiny, materials.size(), false)));
  EXPECT_EQ(streamToFile(ev, materials, tiny, dir.path("tiny-streamed.npy"), 1, false), slurp(dir.path("tiny-one.npy")));
}

// A float32 C-order NPY goes to the device as the file holds it (SampleStream::nextRows,
// Evaluator::evaluateTableRows): its rows are the file's, and a bad row, found on the device, is
// worded as the host reader words it, in whichever chunk it lies, with later bad rows ignored.
TEST(Stream, RawNpyRowsAreWordedAsTheReaderWordsThem) {
  ScratchDir dir("stream");
  const auto materials = someMaterials(6, 8);
  const auto rows = randomRows(3000, true, 6, 31);
  Evaluator ev(runtime(), EvalOptions{});
  {
    const std::string in = dir.path("raw.npy");
    writeFile(in, npyFile(rows, 7, true, false));
    SampleStream stream(in, materials.size(), false);
    ASSERT_TRUE(stream.hasRawRows());
    SampleStream::RawRows raw;
    std::size_t seen = 0;
    while (stream.nextRows(1100, raw)) {
      ASSERT_EQ(raw.firstRow, seen);
      for (std::size_t k = 0; k < 7 * raw.count; ++k)
        ASSERT_EQ(raw.data[k], float(rows[7 * seen + k])) << "row " << seen + k / 7;
      seen += raw.count;
    }
    EXPECT_EQ(seen, 3000u);
  }
  // Not served raw: float64, Fortran order, and files read without a material count (the grid's).
  for (const auto& [name, file, count] : {std::tuple{"f64.npy", npyFile(rows, 7, false, false), materials.size()},
                                          std::tuple{"fortran.npy", npyFile(rows, 7, true, true), materials.size()},
                                          std::tuple{"grid.npy", npyFile(rows, 7, true, false), std::size_t(0)}}) {
    writeFile(dir.path(name), file);
    EXPECT_FALSE(SampleStream(dir.path(name), count, true).hasRawRows()) << name;
  }
  struct Case {
    std::size_t row;
    int column;  // 0: the material index, 1..6: Lx..Vz; -1: V all zero
    double value;
  };
  const Case cases[] = {{1234, 1, NAN},  {1234, 0, 2.5}, {1999, 0, -1.0},         {2999, 0, 6.0},
                        {0, -1, 0.0},    {2001, 6, INFINITY}, {1500, 0, 4294967296.0}};
  for (const auto& c : cases) {
    auto bad = rows;
    if (c.column >= 0) bad[7 * c.row + c.column] = c.value;
    if (c.column < 0) std::fill_n(bad.begin() + std::ptrdiff_t(7 * c.row + 4), 3, 0.0);
    if (c.row + 5 < 3000) bad[7 * (c.row + 5) + 2] = NAN;  // a later bad row must not win
    const std::string in = dir.path("bad.npy");
    writeFile(in, npyFile(bad, 7, true, false));
    const std::string expected = errorOf([&] { readSamples(in, materials.size(), false); });
    ASSERT_NE(expected.find(": row " + std::to_string(c.row) + ": "), std::string::npos) << expected;
    for (std::size_t chunk : {std::size_t(1000), std::size_t(1) << 20})
      for (bool overlap : {true, false})
        EXPECT_EQ(errorOf([&] { streamToFile(ev, materials, in, dir.path("out.npy"), chunk, false, nullptr, overlap); }),
                  expected)
            << "chunk " << chunk << (overlap ? "" : ", serial");
  }
}

// The grid is material-major: a direction file that fits one chunk is read once and evaluated
// for blocks of materials; a larger one is read once per material.
TEST(Stream, ChunkedGridEqualsOneShot) {
  ScratchDir dir("stream");
  const auto materials = someMaterials(5, 10);
  const auto rows = randomRows(1000, false, 1, 11);
  const std::string in = dir.path("d.npy");
  writeFile(in, npyFile(rows, 6, false, false));
  Evaluator ev(runtime(), EvalOptions{});
  writeResults(dir.path("one-shot.npy"), ev.evaluateGrid(materials, readSamples(in, 0, true)));
  const std::string expected = slurp(dir.path("one-shot.npy"));
  struct Case {
    std::size_t chunk, evaluations;
  };
  for (const Case c : {Case{100000, 1}, Case{2000, 3}, Case{1000, 5}, Case{999, 10}, Case{64, 5 * 16}}) {
    StreamStats stats;
    EXPECT_EQ(streamToFile(ev, materials, in, dir.path("streamed.npy"), c.chunk, true, &stats), expected)
        << "chunk " << c.chunk;
    EXPECT_EQ(stats.rows, 5000u);
    EXPECT_EQ(stats.samples, 1000u);
    EXPECT_EQ(stats.chunks, c.evaluations) << "chunk " << c.chunk;
  }
  const std::string csv = dir.path("d.csv");
  writeFile(csv, csvFile(rows, false));
  writeResults(dir.path("one-shot.csv"), ev.evaluateGrid(materials, readSamples(csv, 0, true)));
  EXPECT_EQ(streamToFile(ev, materials, csv, dir.path("streamed.csv"), 333, true), slurp(dir.path("one-shot.csv")));
}

TEST(Stream, RejectsAChunkOutOfRangeAndNoMaterials) {
  ScratchDir dir("stream");
  const std::string in = dir.path("s.csv");
  writeFile(in, csvFile(randomRows(3, true, 1, 12), true));
  Evaluator ev(runtime(), EvalOptions{});
  SampleStream samples(in, 1, false);
  ResultWriter out(dir.path("o.csv"));
  StreamOptions o;
  o.chunk = 0;
  EXPECT_EQ(errorOf([&] { evaluateStream(ev, someMaterials(1, 13), samples, out, o); }),
            "chunk of 0 samples is out of range; use 1 to 268435456");
  o.chunk = 10;
  EXPECT_EQ(errorOf([&] { evaluateStream(ev, {}, samples, out, o); }), "no materials to evaluate");
}

}  // namespace
