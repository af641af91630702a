// Tests of the samples readers (host/src/io): CSV and NPY, every accepted form and every error
// path, with the file name and line or row in each message, and large files split between threads.
#include "io_fixture.hpp"

namespace {

// ---------------------------------------------------------------------------------------------
// Samples: CSV

TEST_F(Io, CsvReadsAndNormalizes) {
  const std::string p = write("s.csv",
                              "\xEF\xBB\xBFmaterial, Lx ,Ly,Lz,Vx,Vy,Vz\r\n"
                              "0,0,0,2,1,0,1\r\n"
                              " 2 , 3 ,\t4, 0 ,0,-5,0\r\n"
                              "1.0,+1e-300,0,0,1e300,1e300,0\r\n"
                              "\r\n\n  \n");
  const Samples s = brdfcl::readSamples(p, 3, false);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s.material, (std::vector<std::uint32_t>{0, 2, 1}));
  const float h = static_cast<float>(1.0 / std::sqrt(2.0));
  const std::vector<float> L = {0, 0, 1, 0.6f, 0.8f, 0, 1, 0, 0};
  const std::vector<float> V = {h, 0, h, 0, -1, 0, h, h, 0};
  ASSERT_EQ(s.L.size(), L.size());
  for (std::size_t i = 0; i < L.size(); ++i) {
    EXPECT_FLOAT_EQ(s.L[i], L[i]) << i;
    EXPECT_FLOAT_EQ(s.V[i], V[i]) << i;
  }
}

TEST_F(Io, CsvQuotedHeaderNames) {
  const std::string p = write("q.csv", "\"material\",\"Lx\",\"Ly\",\"Lz\",\"Vx\",\"Vy\",\"Vz\"\n0,0,0,1,0,0,1\n");
  EXPECT_EQ(brdfcl::readSamples(p, 1, false).size(), 1u);
  const std::string half = write("h.csv", "\"material,Lx,Ly,Lz,Vx,Vy,Vz\n0,0,0,1,0,0,1\n");
  EXPECT_CONTAINS(errorOf([&] { brdfcl::readSamples(half, 1, false); }),
                  half + ": header: unknown column '\"material' (column 1); did you mean material?");
}

TEST_F(Io, CsvWithoutTrailingNewlineAndWithoutMaterialCheck) {
  const std::string p = write("s.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n123,0,0,1,0,0,1");
  const Samples s = brdfcl::readSamples(p, 0, false);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s.material[0], 123u);
}

TEST_F(Io, CsvMaterialColumnOptional) {
  const std::string grid = write("g.csv", "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1\n1,0,1,0,1,1\n");
  const Samples s = brdfcl::readSamples(grid, 2, true);
  EXPECT_EQ(s.size(), 2u);
  EXPECT_TRUE(s.material.empty());

  // Without the option the material column is required.
  const std::string m = errorOf([&] { brdfcl::readSamples(grid, 2, false); });
  EXPECT_CONTAINS(m, grid + ": header: missing column material; add it, or pass --grid");

  // With the option and a material column, indices are read and still range-checked.
  const std::string withMat = write("m.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n1,0,0,1,0,0,1\n");
  EXPECT_EQ(brdfcl::readSamples(withMat, 2, true).material, (std::vector<std::uint32_t>{1}));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(withMat, 1, true); }),
            withMat + ":2: material index 1 out of range (1 material)");

  // Rows of a 6-column file must have 6 fields.
  const std::string short6 = write("s6.csv", "Lx,Ly,Lz,Vx,Vy,Vz\n0,0,1,0,0,1,1\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(short6, 0, true); }),
            short6 + ":2: expected 6 fields (Lx,Ly,Lz,Vx,Vy,Vz), got 7");
}

struct BadCsv {
  const char* body;      // lines after the header
  const char* expected;  // message after "<path>:"
};

TEST_F(Io, CsvRowErrorsNameFileLineAndField) {
  const BadCsv cases[] = {
      {"0,0,0,1,0,0,1\n0,0,0,1,0,0,1\n0,0,1,0,0\n", "4: expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz), got 5"},
      {"0,0,0,1,0,0,1,5\n", "2: expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz), got 8"},
      {"0,0,0,1,0,0,1,\n", "2: expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz), got 8"},
      {"0,0,0,1,0,abc,1\n", "2: field 'Vy' is not a number: 'abc'"},
      {"0,0,0,1,0,,1\n", "2: field 'Vy' is not a number: ''"},
      {"0,0,0,1,0,1 2,1\n", "2: field 'Vy' is not a number: '1 2'"},
      {"0,0x1,0,1,0,0,1\n", "2: field 'Lx' is not a number: '0x1'"},
      {"0,1.5.2,0,1,0,0,1\n", "2: field 'Lx' is not a number: '1.5.2'"},
      {"0,++1,0,1,0,0,1\n", "2: field 'Lx' is not a number: '++1'"},
      {"x,0,0,1,0,0,1\n", "2: field 'material' is not a number: 'x'"},
      {"0,0,0,1,0,0,nan\n", "2: field 'Vz' is not finite: 'nan'"},
      {"0,inf,0,1,0,0,1\n", "2: field 'Lx' is not finite: 'inf'"},
      {"0,0,-1e999,1,0,0,1\n", "2: field 'Ly' is not finite: '-1e999'"},
      {"3.5,0,0,1,0,0,1\n", "2: material index 3.5 is not a non-negative integer"},
      {"-1,0,0,1,0,0,1\n", "2: material index -1 is not a non-negative integer"},
      {"0,0,0,1,0,0,1\n12,0,0,1,0,0,1\n", "3: material index 12 out of range (3 materials)"},
      {"3,0,0,1,0,0,1\n", "2: material index 3 out of range (3 materials)"},
      {"0,0,0,1,0,0,1\n0,0,0,1,0,0,1\n0,0,0,1,0,0,1\n1,0,0,0,0,0,1\n", "5: L has zero length"},
      {"1,0,0,1,-0,0,0\n", "2: V has zero length"},
      {"1,1e-400,0,0,0,0,1\n", "2: L has zero length"},
      {"0,0,0,1,0,0,1\n\n0,0,0,1,0,0,1\n", "3: empty line; expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz)"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.body);
    const std::string p = write("s.csv", std::string("material,Lx,Ly,Lz,Vx,Vy,Vz\n") + c.body);
    EXPECT_EQ(errorOf([&] { brdfcl::readSamples(p, 3, false); }), p + ":" + c.expected);
  }
}

TEST_F(Io, CsvMaterialIndexForms) {
  const std::string p =
      write("s.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n3.0,0,0,1,0,0,1\n2e0,0,0,1,0,0,1\n-0,0,0,1,0,0,1\n");
  EXPECT_EQ(brdfcl::readSamples(p, 4, false).material, (std::vector<std::uint32_t>{3, 2, 0}));
  const std::string huge = write("h.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\n1e10,0,0,1,0,0,1\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(huge, 0, false); }),
            huge + ":2: material index 10000000000 is too large");
}

TEST_F(Io, CsvHeaderAndEmptyFileErrors) {
  const std::string empty = write("e.csv", "");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(empty, 0, false); }),
            empty + ": empty file; expected the header 'material,Lx,Ly,Lz,Vx,Vy,Vz'");
  const std::string blank = write("b.csv", "\n \r\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(blank, 0, true); }),
            blank + ": empty file; expected the header 'material,Lx,Ly,Lz,Vx,Vy,Vz' or 'Lx,Ly,Lz,Vx,Vy,Vz'");
  const std::string headerOnly = write("h.csv", "material,Lx,Ly,Lz,Vx,Vy,Vz\r\n\r\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(headerOnly, 0, false); }),
            headerOnly + ": no samples (the file has a header but no rows)");
  const std::string noHeader = write("n.csv", "0,0,0,1,0,0,1\n");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(noHeader, 0, false); }),
            noHeader + ":1: missing header; the first line must be 'material,Lx,Ly,Lz,Vx,Vy,Vz'");
  const std::string wrongCase = write("w.csv", "material,lx,ly,lz,vx,vy,vz\n0,0,0,1,0,0,1\n");
  EXPECT_EQ(
      errorOf([&] { brdfcl::readSamples(wrongCase, 0, false); }),
      wrongCase + ": header: unknown column 'lx' (column 2); did you mean Lx? the columns are material,Lx,Ly,Lz,Vx,Vy,Vz "
                  "in any order");
  const std::string missing = path("nope.csv");
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(missing, 0, false); }),
            "cannot read samples file '" + missing + "': No such file or directory");
}

TEST_F(Io, CsvManyRowsKeepLineNumbers) {
  std::string body = "material,Lx,Ly,Lz,Vx,Vy,Vz\n";
  for (int i = 0; i < 100000; ++i) body += std::to_string(i % 5) + ",0.1,0.2,0.9,-0.3,0.2,0.8\n";
  const std::string good = write("many.csv", body);
  const Samples s = brdfcl::readSamples(good, 5, false);
  ASSERT_EQ(s.size(), 100000u);
  EXPECT_EQ(s.material[99999], 4u);
  body += "1,0,0,0,0,0,1\n";
  const std::string bad = write("bad.csv", body);
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(bad, 5, false); }), bad + ":100002: L has zero length");
}

// Files of several MiB are split between worker threads (when the machine has several cores):
// order, line numbers and the choice of the first error must not depend on the split.
TEST_F(Io, CsvLargeFileKeepsOrderAndReportsFirstError) {
  const int rows = 200000;
  std::vector<std::string> lines = {"material,Lx,Ly,Lz,Vx,Vy,Vz"};
  for (int i = 0; i < rows; ++i)
    lines.push_back(std::to_string(i % 7) + "," + std::to_string(i) + ",0,1,0," + std::to_string(rows - i) + ",1");
  const auto join = [](const std::vector<std::string>& ls, const std::string& tail) {
    std::string out;
    for (const auto& l : ls) out += l + "\n";
    return out + tail;
  };
  const Samples s = brdfcl::readSamples(write("big.csv", join(lines, std::string(3 << 20, '\n'))), 7, false);
  ASSERT_EQ(s.size(), static_cast<std::size_t>(rows));
  for (int i = 0; i < rows; i += 997) {
    const double lx = i / std::sqrt(double(i) * i + 1.0),
                 vy = (rows - i) / std::sqrt(double(rows - i) * (rows - i) + 1.0);
    ASSERT_EQ(s.material[i], static_cast<std::uint32_t>(i % 7)) << i;
    ASSERT_FLOAT_EQ(s.L[3 * i], static_cast<float>(lx)) << i;
    ASSERT_FLOAT_EQ(s.V[3 * i + 1], static_cast<float>(vy)) << i;
  }

  // Line n of the file is lines[n - 1].
  std::vector<std::string> bad = lines;
  bad[150000] = "0,0,0,0,0,0,1";
  const std::string late = write("late.csv", join(bad, ""));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(late, 7, false); }), late + ":150001: L has zero length");
  bad[10] = "0,0,0,1,x,0,1";
  const std::string both = write("both.csv", join(bad, ""));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(both, 7, false); }), both + ":11: field 'Vx' is not a number: 'x'");
  bad = lines;
  bad[120000] = "";
  const std::string gap = write("gap.csv", join(bad, "\n\n"));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(gap, 7, false); }),
            gap + ":120001: empty line; expected 7 fields (material,Lx,Ly,Lz,Vx,Vy,Vz)");
  bad = lines;
  bad.back() = "9,1,0,0,1,0,0";
  const std::string last = write("last.csv", join(bad, "\r\n"));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(last, 7, false); }),
            last + ":" + std::to_string(rows + 1) + ": material index 9 out of range (7 materials)");
}

// ---------------------------------------------------------------------------------------------
// Samples: NPY

// Builds an .npy file by hand, so the tests pin the format rather than our own writer.
std::string npyBytes(const std::string& descr, bool fortran, const std::string& shape, const std::string& data,
                     int major = 1, const std::string& headerOverride = "") {
  std::string header = headerOverride.empty()
                           ? "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") +
                                 ", 'shape': " + shape + ", }"
                           : headerOverride;
  const std::size_t prefix = major == 1 ? 10 : 12;
  while ((prefix + header.size() + 1) % 64 != 0) header += ' ';
  header += '\n';
  std::string out = std::string("\x93NUMPY", 6) + static_cast<char>(major) + '\0';
  const std::uint32_t len = static_cast<std::uint32_t>(header.size());
  out.append(reinterpret_cast<const char*>(&len), major == 1 ? 2 : 4);
  return out + header + data;
}

template <typename T>
std::string raw(const std::vector<T>& v) {
  return std::string(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}

const std::vector<double> kRows = {0, 0, 0, 2, 1, 0,  1,  //
                                   2, 3, 4, 0, 0, -5, 0};

void expectTwoRows(const Samples& s, bool withMaterial) {
  ASSERT_EQ(s.size(), 2u);
  if (withMaterial) {
    EXPECT_EQ(s.material, (std::vector<std::uint32_t>{0, 2}));
  }
  const float h = static_cast<float>(1.0 / std::sqrt(2.0));
  const std::vector<float> L = {0, 0, 1, 0.6f, 0.8f, 0}, V = {h, 0, h, 0, -1, 0};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_FLOAT_EQ(s.L[i], L[i]) << i;
    EXPECT_FLOAT_EQ(s.V[i], V[i]) << i;
  }
}

std::vector<double> transpose(const std::vector<double>& rowMajor, std::size_t rows, std::size_t cols) {
  std::vector<double> out(rowMajor.size());
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) out[j * rows + i] = rowMajor[i * cols + j];
  return out;
}

TEST_F(Io, NpyFloat32AndFloat64AllVersionsAndOrders) {
  const std::vector<float> f32(kRows.begin(), kRows.end());
  const std::vector<double> fortran64 = transpose(kRows, 2, 7);
  const std::vector<float> fortran32(fortran64.begin(), fortran64.end());
  for (int major : {1, 2, 3}) {
    SCOPED_TRACE(major);
    expectTwoRows(brdfcl::readSamples(write("a.npy", npyBytes("<f4", false, "(2, 7)", raw(f32), major)), 3, false),
                  true);
    expectTwoRows(brdfcl::readSamples(write("b.npy", npyBytes("<f8", false, "(2, 7)", raw(kRows), major)), 3, false),
                  true);
    expectTwoRows(brdfcl::readSamples(write("c.npy", npyBytes("<f8", true, "(2, 7)", raw(fortran64), major)), 3, false),
                  true);
    expectTwoRows(brdfcl::readSamples(write("d.npy", npyBytes("<f4", true, "(2, 7)", raw(fortran32), major)), 3, false),
                  true);
  }
  expectTwoRows(brdfcl::readSamples(write("e.npy", npyBytes("|f4", false, "(2, 7)", raw(f32))), 3, false), true);
  expectTwoRows(brdfcl::readSamples(write("f.NPY", npyBytes("=f8", false, "(2, 7)", raw(kRows))), 3, false), true);
  // Python 2 numpy wrote long integers with an L suffix and double-quoted nothing; both forms parse.
  expectTwoRows(brdfcl::readSamples(
                    write("g.npy", npyBytes("", false, "", raw(f32), 1,
                                            "{\"descr\": \"<f4\", \"shape\": (2L, 7L), \"fortran_order\": False}")),
                    3, false),
                true);
}

TEST_F(Io, NpyWithoutMaterialColumn) {
  std::vector<double> six;
  for (std::size_t i = 0; i < kRows.size(); ++i)
    if (i % 7 != 0) six.push_back(kRows[i]);
  const std::string p = write("g.npy", npyBytes("<f8", false, "(2, 6)", raw(six)));
  const Samples s = brdfcl::readSamples(p, 3, true);
  EXPECT_TRUE(s.material.empty());
  expectTwoRows(s, false);
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(p, 3, false); }),
            p + ": expected shape (N, 7) with columns material,Lx,Ly,Lz,Vx,Vy,Vz, got (2, 6); without the material "
                "column, pass --grid to evaluate every material at each direction pair");
  const std::string f = write("f.npy", npyBytes("<f8", true, "(2, 6)", raw(transpose(six, 2, 6))));
  expectTwoRows(brdfcl::readSamples(f, 3, true), false);
  // A 7-column file in optional mode still has its material indices range-checked.
  const std::string seven = write("s.npy", npyBytes("<f8", false, "(2, 7)", raw(kRows)));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(seven, 2, true); }),
            seven + ": row 1: material index 2 out of range (2 materials)");
}

TEST_F(Io, NpyHeaderErrors) {
  const std::vector<float> f32(kRows.begin(), kRows.end());
  struct Case {
    std::string bytes;
    std::string expected;  // message after "<path>: "
  };
  const std::vector<Case> cases = {
      {"material,Lx,Ly,Lz,Vx,Vy,Vz\n", "not an NPY file (no \\x93NUMPY magic); save it with numpy.save"},
      {"", "not an NPY file"},
      {npyBytes(">f4", false, "(2, 7)", raw(f32)),
       "big-endian data ('>f4') is not supported; convert with arr.astype('<f4')"},
      {npyBytes(">f8", false, "(2, 7)", raw(kRows)), "big-endian data ('>f8') is not supported"},
      {npyBytes("<i8", false, "(2, 7)", raw(kRows)),
       "unsupported dtype '<i8'; expected float32 ('<f4') or float64 ('<f8')"},
      {npyBytes("<f2", false, "(2, 7)", raw(kRows)), "unsupported dtype '<f2'"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (2,), }"),
       "structured dtypes are not supported"},
      {npyBytes("<f8", false, "(14,)", raw(kRows)),
       "expected shape (N, 7) with columns material,Lx,Ly,Lz,Vx,Vy,Vz, got (14,)"},
      {npyBytes("<f8", false, "(2, 7, 1)", raw(kRows)), "got (2, 7, 1)"},
      {npyBytes("<f8", false, "(7, 2)", raw(kRows)), "got (7, 2)"},
      {npyBytes("<f8", false, "(0, 7)", ""), "no samples (shape (0, 7))"},
      {npyBytes("<f4", false, "(1000, 7)", std::string(872 * 28 + 5, '\0')),
       "truncated: expected 1000 rows of 7 float32, file has 872 complete rows"},
      {npyBytes("<f8", false, "(3, 7)", raw(kRows)), "truncated: expected 3 rows of 7 float64, file has 2 complete rows"},
      {npyBytes("<f8", false, "(18446744073709551615, 7)", raw(kRows)),
       "truncated: expected 18446744073709551615 rows of 7 float64, file has 2 complete rows"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr': '<f8', 'shape': (2, 7)}"),
       "malformed NPY header (needs 'descr', 'fortran_order' and 'shape')"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr': '<f8', 'fortran_order': maybe, 'shape': (2, 7)}"),
       "malformed NPY header (fortran_order must be True or False)"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (2, -7)}"),
       "malformed NPY header (shape must be a tuple of non-negative integers)"},
      {npyBytes("", false, "", raw(kRows), 1, "descr"), "malformed NPY header (expected '{')"},
      {npyBytes("", false, "", raw(kRows), 1, "{'descr: '<f8'}"), "malformed NPY header"},
      {npyBytes("<f8", false, "(2, 7)", raw(kRows), 4),
       "unsupported NPY format version 4.0 (supported: 1.0, 2.0, 3.0)"},
      {std::string("\x93NUMPY\x01\x00\xff\x00{'descr'", 18), "truncated NPY header"},
      {std::string("\x93NUMPY\x02\x00\x05", 9) + std::string(1, '\0'), "truncated NPY header"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.expected);
    const std::string p = write("bad.npy", c.bytes);
    const std::string m = errorOf([&] { brdfcl::readSamples(p, 3, false); });
    EXPECT_EQ(m.rfind(p + ": ", 0), 0u) << m;
    EXPECT_CONTAINS(m, c.expected);
  }
  // The exact truncation message the docs quote.
  const std::string p = write("s.npy", npyBytes("<f4", false, "(1000, 7)", std::string(872 * 28, '\0')));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(p, 3, false); }),
            p + ": truncated: expected 1000 rows of 7 float32, file has 872 complete rows");
}

TEST_F(Io, NpyRowErrorsUseZeroBasedRows) {
  const auto rowError = [&](std::size_t badRow, std::size_t col, double value, std::size_t materialCount = 3) {
    std::vector<double> rows;
    for (std::size_t i = 0; i < 20; ++i) rows.insert(rows.end(), {1, 0, 0, 1, 0, 0, 1});
    rows[badRow * 7 + col] = value;
    const std::string p = write("r.npy", npyBytes("<f8", false, "(20, 7)", raw(rows)));
    const std::string m = errorOf([&] { brdfcl::readSamples(p, materialCount, false); });
    EXPECT_EQ(m.rfind(p + ": row " + std::to_string(badRow) + ": ", 0), 0u) << m;
    return m.substr(std::min(m.size(), p.size()));
  };
  EXPECT_EQ(rowError(12, 0, 12), ": row 12: material index 12 out of range (3 materials)");
  EXPECT_EQ(rowError(0, 0, 3.5), ": row 0: material index 3.5 is not a non-negative integer");
  EXPECT_EQ(rowError(19, 0, -1), ": row 19: material index -1 is not a non-negative integer");
  EXPECT_EQ(rowError(5, 5, std::nan("")), ": row 5: field 'Vy' is not finite: nan");
  EXPECT_EQ(rowError(5, 1, -INFINITY), ": row 5: field 'Lx' is not finite: -inf");
  EXPECT_EQ(rowError(7, 3, 0), ": row 7: L has zero length");
  EXPECT_EQ(rowError(8, 6, 0), ": row 8: V has zero length");
  EXPECT_EQ(rowError(3, 0, 1e12, 0), ": row 3: material index 1000000000000 is too large");

  // Fortran order: the bad value is found at the same (0-based) row.
  std::vector<float> rows;
  for (std::size_t i = 0; i < 4; ++i) rows.insert(rows.end(), {0, 0, 0, 1, 0, 0, 1});
  rows[2 * 7 + 3] = 0;
  std::vector<double> asDouble(rows.begin(), rows.end());
  const std::vector<double> t = transpose(asDouble, 4, 7);
  const std::string p = write("f.npy", npyBytes("<f4", true, "(4, 7)", raw(std::vector<float>(t.begin(), t.end()))));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(p, 3, false); }), p + ": row 2: L has zero length");
}

TEST_F(Io, NpyLargeFileKeepsOrderAndReportsFirstError) {
  const std::size_t rows = 300000;
  std::vector<double> data(rows * 7);
  for (std::size_t i = 0; i < rows; ++i) {
    const double row[7] = {double(i % 3), double(i), 0, 1, 1, 0, double(i)};
    std::copy(row, row + 7, data.begin() + static_cast<std::ptrdiff_t>(7 * i));
  }
  const auto check = [&](const Samples& s) {
    ASSERT_EQ(s.size(), rows);
    for (std::size_t i = 0; i < rows; i += 1009) {
      ASSERT_EQ(s.material[i], i % 3) << i;
      ASSERT_FLOAT_EQ(s.L[3 * i], static_cast<float>(i / std::sqrt(double(i) * i + 1.0))) << i;
      ASSERT_FLOAT_EQ(s.V[3 * i + 2], static_cast<float>(i / std::sqrt(double(i) * i + 1.0))) << i;
    }
  };
  const std::vector<float> f32(data.begin(), data.end());
  check(brdfcl::readSamples(write("c.npy", npyBytes("<f4", false, "(300000, 7)", raw(f32))), 3, false));
  const std::vector<double> t = transpose(data, rows, 7);
  check(brdfcl::readSamples(write("f.npy", npyBytes("<f8", true, "(300000, 7)", raw(t))), 3, false));

  data[7 * 250000 + 4] = 0;  // V = (0, 0, 250000): fine
  data[7 * 250000 + 6] = 0;  // V = 0: not
  const std::string late = write("late.npy", npyBytes("<f8", false, "(300000, 7)", raw(data)));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(late, 3, false); }), late + ": row 250000: V has zero length");
  data[7 * 20] = 7;
  const std::string both = write("both.npy", npyBytes("<f8", false, "(300000, 7)", raw(data)));
  EXPECT_EQ(errorOf([&] { brdfcl::readSamples(both, 3, false); }),
            both + ": row 20: material index 7 out of range (3 materials)");
}

}  // namespace
