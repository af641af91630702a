// Tests of the results writers and atomic writes (host/src/io): NPY and CSV round trips, replaced
// files, and failures that leave nothing behind.
#include "io_fixture.hpp"

namespace {

// ---------------------------------------------------------------------------------------------
// Results and atomic writes

// Minimal reader for what writeResults produces: v1.0, '<f4', C order, shape (N, 3).
std::vector<float> readNpyResults(const std::string& bytes, std::size_t& rows) {
  if (bytes.size() < 10) {
    ADD_FAILURE() << "not an NPY file: " << bytes.size() << " bytes";
    return {};
  }
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t hlen = static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8;
  EXPECT_EQ((10 + hlen) % 64, 0u);
  const std::string header = bytes.substr(10, hlen);
  EXPECT_EQ(header.back(), '\n');
  EXPECT_NE(header.find("'descr': '<f4'"), std::string::npos) << header;
  EXPECT_NE(header.find("'fortran_order': False"), std::string::npos) << header;
  const std::size_t open = header.find("'shape': (");
  EXPECT_NE(open, std::string::npos) << header;
  rows = std::stoull(header.substr(open + 10));
  EXPECT_NE(header.find(", 3)", open), std::string::npos) << header;
  std::vector<float> data((bytes.size() - 10 - hlen) / 4);
  EXPECT_EQ(data.size(), rows * 3);
  if (!data.empty()) std::memcpy(data.data(), bytes.data() + 10 + hlen, data.size() * 4);
  return data;
}

TEST_F(Io, WriteResultsNpyRoundTrip) {
  std::vector<float> rgb;
  for (int i = 0; i < 3000; ++i) rgb.push_back(static_cast<float>(i) * 0.37f - 5.0f);
  rgb[7] = 1e-30f;
  const std::string p = path("out.npy");
  brdfcl::writeResults(p, rgb);
  std::size_t rows = 0;
  const std::vector<float> back = readNpyResults(readFile(p), rows);
  EXPECT_EQ(rows, 1000u);
  EXPECT_EQ(back, rgb);
  EXPECT_EQ(listDir(), (std::vector<std::string>{"out.npy"}));

  // The reader accepts what the writer produces once it has the 7 columns it needs.
  brdfcl::writeResults(path("empty.NPY"), {});
  const std::string empty = readFile(path("empty.NPY"));
  std::size_t emptyRows = 1;
  EXPECT_TRUE(readNpyResults(empty, emptyRows).empty());
  EXPECT_EQ(emptyRows, 0u);
}

TEST_F(Io, WriteResultsCsvUsesNineSignificantDigits) {
  const std::vector<float> rgb = {0.1f, 1.0f, 0.0f, 123456789.0f, 1e-10f, -2.5f, 3.14159265f, 1e30f, 65504.0f};
  const std::string p = path("out.csv");
  brdfcl::writeResults(p, rgb);
  std::string expected = "r,g,b\n";
  char line[128];
  for (std::size_t i = 0; i < rgb.size(); i += 3) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g\n", rgb[i], rgb[i + 1], rgb[i + 2]);
    expected += line;
  }
  EXPECT_EQ(readFile(p), expected);
  EXPECT_EQ(readFile(p).substr(0, 31), "r,g,b\n0.100000001,1,0\n123456792");
  // Values read back are bit-identical.
  std::istringstream in(readFile(p).substr(6));
  for (float want : rgb) {
    double got = 0;
    char sep;
    in >> got;
    in.get(sep);
    EXPECT_EQ(static_cast<float>(got), want);
  }
}

TEST_F(Io, WriteResultsReplacesExistingFile) {
  const std::string p = write("out.csv", "old content that is longer than the new one\n\n\n\n");
  brdfcl::writeResults(p, {1, 2, 3});
  EXPECT_EQ(readFile(p), "r,g,b\n1,2,3\n");
  EXPECT_EQ(listDir(), (std::vector<std::string>{"out.csv"}));
}

TEST_F(Io, WriteResultsRejectsPartialTriples) {
  EXPECT_THROW(brdfcl::writeResults(path("x.csv"), {1, 2}), std::invalid_argument);
  EXPECT_TRUE(listDir().empty());
}

TEST_F(Io, WriteToMissingDirectoryFailsCleanly) {
  const std::string p = path("out/x.csv");
  EXPECT_EQ(errorOf([&] {
              brdfcl::writeResults(p, {1, 2, 3});
            }),
            "cannot write '" + p + "': No such file or directory");
  EXPECT_TRUE(listDir().empty());
  EXPECT_EQ(errorOf([&] {
              brdfcl::writeResults(dir_.string(), {1, 2, 3});
            }),
            "cannot write '" + dir_.string() + "': it is a directory; name a file inside it");
  fs::create_directory(dir_ / "sub");
  EXPECT_EQ(errorOf([&] {
              brdfcl::writeResults(path("sub"), {1, 2, 3});
            }),
            "cannot write '" + path("sub") + "': it is a directory; name a file inside it");
  EXPECT_EQ(listDir(), (std::vector<std::string>{"sub"}));
}

TEST_F(Io, WriteToReadOnlyDirectoryFailsCleanly) {
  if (::geteuid() == 0) GTEST_SKIP() << "root ignores directory permissions";
  fs::create_directory(dir_ / "ro");
  fs::permissions(dir_ / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  const std::string p = path("ro/x.csv");
  EXPECT_EQ(errorOf([&] { brdfcl::writeResults(p, {1, 2, 3}); }), "cannot write '" + p + "': Permission denied");
  fs::permissions(dir_ / "ro", fs::perms::owner_all);
  EXPECT_TRUE(fs::is_empty(dir_ / "ro"));
}

// Stands in for a full disk: with RLIMIT_FSIZE, write() fails with EFBIG the way it fails with
// ENOSPC, and the writer must notice, report the user's path and leave nothing behind.
TEST_F(Io, WriteFailureMidwayLeavesNoFile) {
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto oldHandler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::vector<float> rgb(300000, 0.123456789f);
  const std::string csv = path("big.csv"), npy = path("big.npy");
  const std::string m1 = errorOf([&] { brdfcl::writeResults(csv, rgb); });
  const std::string m2 = errorOf([&] { brdfcl::writeResults(npy, rgb); });
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, oldHandler);
  EXPECT_EQ(m1, "cannot write '" + csv + "': File too large");
  EXPECT_EQ(m2, "cannot write '" + npy + "': File too large");
  EXPECT_TRUE(listDir().empty());
}

TEST_F(Io, WriteAtomicallyUsesHiddenTemporaryBeside) {
  const std::string p = path("result.bin");
  std::string seen;
  brdfcl::writeAtomically(p, [&](const std::string& tmp) {
    seen = tmp;
    EXPECT_TRUE(fs::exists(tmp));
    EXPECT_FALSE(fs::exists(p));
    std::ofstream(tmp, std::ios::binary) << "payload";
  });
  EXPECT_EQ(fs::path(seen).parent_path(), dir_);
  EXPECT_EQ(fs::path(seen).filename().string().rfind(".brdfcl.tmp.", 0), 0u) << seen;
  EXPECT_EQ(readFile(p), "payload");
  EXPECT_EQ(listDir(), (std::vector<std::string>{"result.bin"}));
}

TEST_F(Io, WriteAtomicallyRemovesTemporaryOnException) {
  const std::string p = write("keep.csv", "previous\n");
  struct Boom : std::runtime_error {
    Boom() : std::runtime_error("boom") {}
  };
  EXPECT_THROW(brdfcl::writeAtomically(p,
                                       [&](const std::string& tmp) {
                                         std::ofstream(tmp) << "half";
                                         throw Boom();
                                       }),
               Boom);
  EXPECT_EQ(readFile(p), "previous\n");
  EXPECT_EQ(listDir(), (std::vector<std::string>{"keep.csv"}));

  const std::string fresh = path("fresh.csv");
  EXPECT_THROW(brdfcl::writeAtomically(fresh, [](const std::string&) { throw Error("inner"); }), Error);
  EXPECT_EQ(listDir(), (std::vector<std::string>{"keep.csv"}));
}

TEST_F(Io, WriteAtomicallyRelativePathInCurrentDirectory) {
  const fs::path old = fs::current_path();
  fs::current_path(dir_);
  brdfcl::writeResults("rel.csv", {0.5f, 0.25f, 0.125f});
  fs::current_path(old);
  EXPECT_EQ(readFile(path("rel.csv")), "r,g,b\n0.5,0.25,0.125\n");
}

}  // namespace
