// NPY results written to a regular file go to the disk with O_DIRECT (io/results.cpp): the bytes
// must be exactly those of a buffered write for every length and chunking, the pages must stay out
// of the page cache where the filesystem takes O_DIRECT, and a filesystem without it must still work.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "brdfcl/io.hpp"
#include "npy.hpp"
#include "process.hpp"

namespace brdfcl::test {
namespace {

std::string readAll(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// What numpy.save writes for float32 (rows, 3): written out here, not by the writer under test.
std::string expectedNpy(const std::vector<float>& rgb) {
  std::string out = npyHeader(rgb.size() / 3, 3);
  out.append(reinterpret_cast<const char*>(rgb.data()), rgb.size() * sizeof(float));
  return out;
}

void expectFileIs(const std::string& p, const std::string& want, const std::string& what) {
  const std::string got = readAll(p);
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i)
    ASSERT_EQ(got[i], want[i]) << what << ": byte " << i << " of " << got.size();
}

// Lengths below, at and across the 1 MiB buffer and the 4 KiB blocks, appended in uneven chunks.
TEST(DirectOutput, NpyBytesAreThoseOfABufferedWrite) {
  ScratchDir dir("direct");
  const std::size_t kRowsPerMiB = (std::size_t(1) << 20) / 12;
  for (std::size_t rows : {std::size_t(0), std::size_t(1), std::size_t(331), std::size_t(4096 / 12 + 1), kRowsPerMiB,
                           kRowsPerMiB + 1, 3 * kRowsPerMiB + 977, std::size_t(700001)}) {
    const std::vector<float> rgb = randomRgb(rows, rows + 1);
    for (std::size_t chunk : {std::size_t(1000), std::size_t(87381), std::size_t(1) << 20}) {
      const std::string p = dir.path("r.npy");
      ResultWriter w(p);
      for (std::size_t first = 0; first < rows; first += chunk)
        w.append(rgb.data() + 3 * first, std::min(chunk, rows - first));
      w.commit();
      expectFileIs(p, expectedNpy(rgb), std::to_string(rows) + " rows in chunks of " + std::to_string(chunk));
    }
  }
  EXPECT_EQ(dir.list(), std::vector<std::string>{"r.npy"});
}

// On a local disk's filesystem the written blocks never enter the page cache: mincore sees only the
// last, partial block and the header's (written through the cache) resident.
TEST(DirectOutput, LargeNpyResultsBypassThePageCache) {
  ScratchDir dir("direct");
  struct statfs fs {};
  ASSERT_EQ(::statfs(dir.dir().c_str(), &fs), 0);
  const long type = static_cast<long>(fs.f_type);
  if (type != 0xEF53 && type != 0x58465342 && type != 0x9123683E)
    GTEST_SKIP() << dir.dir() << " is not on ext4, XFS or btrfs (f_type 0x" << std::hex << type
                 << "), where results are written with O_DIRECT";
  const std::size_t rows = 1 << 20;  // 12 MiB
  const std::vector<float> rgb = randomRgb(rows, 5);
  const std::string p = dir.path("big.npy");
  ResultWriter w(p);
  w.append(rgb.data(), rows);
  w.commit();
  const int fd = ::open(p.c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  struct stat st {};
  ASSERT_EQ(::fstat(fd, &st), 0);
  void* m = ::mmap(nullptr, std::size_t(st.st_size), PROT_READ, MAP_SHARED, fd, 0);
  ASSERT_NE(m, MAP_FAILED);
  const long page = ::sysconf(_SC_PAGESIZE);
  const std::size_t pages = (std::size_t(st.st_size) + std::size_t(page) - 1) / std::size_t(page);
  std::vector<unsigned char> resident(pages);
  ASSERT_EQ(::mincore(m, std::size_t(st.st_size), resident.data()), 0);
  std::size_t cached = 0;
  for (unsigned char r : resident) cached += r & 1;
  ::munmap(m, std::size_t(st.st_size));
  ::close(fd);
  EXPECT_LE(cached, 4u) << cached << " of " << pages << " pages are in the page cache";
  expectFileIs(p, expectedNpy(rgb), "12 MiB");
}

// tmpfs refuses O_DIRECT: the writer falls back to the page cache and the bytes are the same.
TEST(DirectOutput, FilesystemsWithoutODirectGetBufferedWrites) {
  struct statfs fs {};
  if (::statfs("/dev/shm", &fs) != 0 || ::access("/dev/shm", W_OK) != 0) GTEST_SKIP() << "no writable /dev/shm";
  const std::string p = "/dev/shm/brdfcl-direct-" + std::to_string(::getpid()) + ".npy";
  const std::vector<float> rgb = randomRgb(300001, 9);
  {
    ResultWriter w(p);
    w.append(rgb.data(), 100000);
    w.append(rgb.data() + 300000, 200001);
    w.commit();
  }
  expectFileIs(p, expectedNpy(rgb), "/dev/shm");
  ::unlink(p.c_str());
}

}  // namespace
}  // namespace brdfcl::test
