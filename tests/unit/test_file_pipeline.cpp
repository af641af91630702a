// The NPY file pipeline's shortcuts: results written to the disk from the device's own buffer
// (ResultWriter::appendInPlace), the first chunk read ahead while the device opens
// (SampleStream::readAhead) and uninitialized, huge-page chunk buffers, each against the plain path.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "brdfcl/stream.hpp"
#include "npy.hpp"
#include "process.hpp"
#include "stream_files.hpp"
#include "support.hpp"

namespace brdfcl::test {
namespace {

std::string expectedNpy(const std::vector<float>& rgb) {
  std::string out = npyHeader(rgb.size() / 3, 3);
  out.append(reinterpret_cast<const char*>(rgb.data()), rgb.size() * sizeof(float));
  return out;
}

void expectBytes(const std::string& got, const std::string& want, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  const auto diff = std::mismatch(got.begin(), got.end(), want.begin());
  ASSERT_TRUE(diff.first == got.end()) << what << ": first different byte " << (diff.first - got.begin());
}

// appendInPlace with the rows placed where they go to the disk as they lie (aligned to their file
// offset) and where they cannot (off by a float), mixed with append(), for chunk lengths that
// leave every kind of partial block: the bytes are those numpy would write.
TEST(FilePipeline, InPlaceAppendsWriteTheSameBytesWhereverTheRowsLie) {
  ScratchDir dir("pipeline");
  constexpr std::size_t kHead = ResultWriter::kInPlaceHeadroom;
  for (std::size_t chunk : {std::size_t(341), std::size_t(342), std::size_t(1000), std::size_t(87381),
                            std::size_t(65536), std::size_t(250001)}) {
    for (int placement = 0; placement < 3; ++placement) {  // aligned, misaligned, alternating with append()
      const std::size_t rows = 3 * chunk + 777;
      const std::vector<float> rgb = randomRgb(rows, chunk + 13 * placement);
      const std::string p = dir.path("r.npy");
      ResultWriter w(p);
      std::vector<float> scratch((2 * kHead + 12 * chunk) / sizeof(float) + 1);
      std::size_t offset = w.appendOffset(), k = 0;
      for (std::size_t first = 0; first < rows; first += chunk, ++k) {
        const std::size_t n = std::min(chunk, rows - first);
        if (placement == 2 && k % 2 == 1) {
          w.append(rgb.data() + 3 * first, n);
        } else {
          const std::size_t misalign = (offset - reinterpret_cast<std::uintptr_t>(scratch.data())) % kHead;
          float* at = scratch.data() + (kHead + misalign) / sizeof(float) + (placement == 1 ? 1 : 0);
          std::memcpy(at, rgb.data() + 3 * first, 12 * n);
          w.appendInPlace(at, n);
        }
        offset += 12 * n;
      }
      EXPECT_EQ(w.rows(), rows);
      w.commit();
      expectBytes(slurp(p), expectedNpy(rgb),
                  std::to_string(rows) + " rows in chunks of " + std::to_string(chunk) + ", placement " +
                      std::to_string(placement));
    }
  }
}

// A many-chunk NPY through the whole pipeline (read ahead, table rows on the device, results in
// place), with an input header longer than numpy's usual and a last chunk and block both partial,
// is bit for bit the in-memory evaluation of the same rows.
TEST(FilePipeline, ManyChunksEqualTheInMemoryEvaluation) {
  ScratchDir dir("pipeline");
  std::mt19937_64 rng(seed() + 41);
  std::vector<MaterialParams> materials;
  for (int i = 0; i < 5; ++i) materials.push_back(randomMaterial(rng));
  const std::size_t n = 120001;
  const auto rows = randomRows(n, true, 5, 42);
  const std::string in = dir.path("s.npy");
  // An extra key makes the header 192 bytes instead of 128: the data start elsewhere in a block.
  std::string file = npyWithDict("{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(n) +
                                 ", 7), 'note': '" + std::string(80, 'x') + "', }");
  const std::string body = npyFile(rows, 7, true, false);
  file += body.substr(npyHeader(n, 7).size());
  writeFile(in, file);
  Evaluator ev(runtime(), EvalOptions{});
  const std::vector<float> expected = ev.evaluate(materials, readSamples(in, materials.size(), false));
  for (std::size_t chunk : {std::size_t(7777), std::size_t(32768), std::size_t(50000)}) {
    for (bool ahead : {false, true}) {
      const std::string out = dir.path("o.npy");
      SampleStream samples(in, materials.size(), false);
      if (ahead) samples.readAhead(chunk);
      ResultWriter writer(out);
      StreamOptions o;
      o.chunk = chunk;
      const StreamStats s = evaluateStream(ev, materials, samples, writer, o);
      writer.commit();
      EXPECT_EQ(s.rows, n);
      expectBytes(slurp(out), expectedNpy(expected),
                  "chunk " + std::to_string(chunk) + (ahead ? ", read ahead" : ""));
    }
  }
}

// A chunk read ahead is the one nextRows(maxRows) returns; asked for anything else, the stream
// drops it and serves what it would have served without it.
TEST(FilePipeline, ReadAheadServesTheSameRowsWhateverIsAskedNext) {
  ScratchDir dir("pipeline");
  const auto rows = randomRows(1000, true, 3, 43);
  const std::string in = dir.path("s.npy");
  writeFile(in, npyFile(rows, 7, true, false));
  auto rowAt = [&](std::size_t i, std::size_t k) { return float(rows[7 * i + k]); };
  {
    SampleStream s(in, 3, false);
    s.readAhead(400);
    SampleStream::RawRows raw;
    ASSERT_TRUE(s.nextRows(400, raw));
    EXPECT_EQ(raw.firstRow, 0u);
    EXPECT_EQ(raw.count, 400u);
    EXPECT_EQ(raw.data[7 * 399 + 6], rowAt(399, 6));
    ASSERT_TRUE(s.nextRows(400, raw));
    EXPECT_EQ(raw.firstRow, 400u);
    EXPECT_EQ(raw.data[0], rowAt(400, 0));
  }
  {
    SampleStream s(in, 3, false);
    s.readAhead(400);
    SampleStream::RawRows raw;
    ASSERT_TRUE(s.nextRows(60, raw));  // a different size: the read-ahead rows are dropped
    EXPECT_EQ(raw.firstRow, 0u);
    EXPECT_EQ(raw.count, 60u);
    ASSERT_TRUE(s.nextRows(1000, raw));
    EXPECT_EQ(raw.firstRow, 60u);
    EXPECT_EQ(raw.count, 940u);
  }
  {
    SampleStream s(in, 3, false);
    s.readAhead(400);
    Samples got;
    ASSERT_TRUE(s.next(50, got));  // the checked reader starts from the first row too
    Samples want;
    SampleStream plain(in, 3, false);
    ASSERT_TRUE(plain.next(50, want));
    EXPECT_EQ(got.material, want.material);
    EXPECT_EQ(got.L, want.L);
    s.rewind();
    s.readAhead(10);
    s.rewind();
    SampleStream::RawRows raw;
    ASSERT_TRUE(s.nextRows(10, raw));
    EXPECT_EQ(raw.firstRow, 0u);
  }
}

// A file cut short gives the reader's one-line error whether the cut is before the chunk read
// ahead or between two chunks.
TEST(FilePipeline, AFileCutShortIsAnErrorAfterAReadAhead) {
  ScratchDir dir("pipeline");
  const std::string p = dir.path("cut.npy");
  const std::string want = p + ": truncated while reading (was the file changed during the run?)";
  writeFile(p, npyFile(randomRows(1000, true, 2, 44), 7, true, false));
  {
    SampleStream s(p, 2, false);
    ASSERT_EQ(::truncate(p.c_str(), 128 + 28 * 300), 0);
    s.readAhead(400);
    SampleStream::RawRows raw;
    EXPECT_EQ(errorOf([&] { s.nextRows(400, raw); }), want);
  }
  writeFile(p, npyFile(randomRows(1000, true, 2, 44), 7, true, false));
  {
    SampleStream s(p, 2, false);
    s.readAhead(400);
    SampleStream::RawRows raw;
    ASSERT_TRUE(s.nextRows(400, raw));
    ASSERT_EQ(::truncate(p.c_str(), 128 + 28 * 500), 0);
    EXPECT_EQ(errorOf([&] { s.nextRows(400, raw); }), want);
  }
}

// Chunk buffers of 2 MiB and more start on a 2 MiB boundary (what transparent huge pages need);
// small ones come from the heap; both hold what is written.
TEST(FilePipeline, ChunkBuffersAreHugePageAligned) {
  for (std::size_t n : {std::size_t(1), std::size_t(1000), std::size_t(1) << 19, (std::size_t(7) << 20) + 3}) {
    ChunkVector<float> v(n);
    v.back() = 1.5f;
    v.front() = 2.5f;
    EXPECT_EQ(v.back(), n == 1 ? 2.5f : 1.5f);
    if (n * sizeof(float) >= (std::size_t(2) << 20))
      EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % (std::size_t(2) << 20), 0u) << n;
  }
}

}  // namespace
}  // namespace brdfcl::test
