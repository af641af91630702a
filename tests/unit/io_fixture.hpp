// What the file I/O tests share (test_io, test_io_samples, test_io_results): the fixture that gives
// each test its own temporary directory, removed afterwards (tempdir_fixture.hpp), and a whole-file reader.
#pragma once

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "support.hpp"
#include "tempdir_fixture.hpp"
#include "brdfcl/error.hpp"
#include "brdfcl/io.hpp"
#include "brdfcl/material.hpp"

namespace fs = std::filesystem;
using brdfcl::Error;
using brdfcl::test::errorOf;
using brdfcl::MaterialParams;
using brdfcl::Samples;

// A named namespace, not an anonymous one: the fixtures must be one class in every test file
// (GoogleTest refuses a suite whose fixture differs between translation units).
namespace io_test {

class Io : public brdfcl::test::TempDirTest {
 protected:
  Io() : TempDirTest("io") {}
};

using brdfcl::test::readFile;

}  // namespace io_test

using namespace io_test;
