// What the file fixtures of the I/O tests share (io_fixture.hpp, gbuffer_fixture.hpp): a GoogleTest
// fixture that gives each test its own temporary directory, removed afterwards, with helpers to
// name, write and list files in it, and a whole-file reader.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace brdfcl::test {

inline std::atomic<int> tempDirCounter{0};

// The directory is brdfcl-<tag>-<pid>-<test name>-<n> under the system temp dir.
class TempDirTest : public ::testing::Test {
 protected:
  explicit TempDirTest(std::string tag) : tag_(std::move(tag)) {}

  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() / ("brdfcl-" + tag_ + "-" + std::to_string(::getpid()) + "-" +
                                                     info->name() + "-" + std::to_string(tempDirCounter++));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write(const std::string& name, const std::string& content) const {
    const std::string p = path(name);
    std::ofstream(p, std::ios::binary) << content;
    return p;
  }

  std::vector<std::string> listDir() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir_)) names.push_back(e.path().filename().string());
    return names;
  }

  std::filesystem::path dir_;

 private:
  std::string tag_;
};

// The whole file as bytes ("" when it cannot be read).
inline std::string readFile(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace brdfcl::test
