// What the file I/O tests share (test_io, test_io_samples, test_io_results): the fixture that gives
// each test its own temporary directory, removed afterwards, and a whole-file reader.
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

inline std::atomic<int> dirCounter{0};

class Io : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("brdfcl-io-" + std::to_string(::getpid()) + "-" + info->name() + "-" + std::to_string(dirCounter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write(const std::string& name, const std::string& content) const {
    const std::string p = path(name);
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }

  std::vector<std::string> listDir() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }

  fs::path dir_;
};


inline std::string readFile(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace io_test

using namespace io_test;
