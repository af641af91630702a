// The built CLI run as a child process in a scratch folder, and the check of a refusal: exit
// status 2 and one line on stderr holding the expected text (the CLI's error contract).
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "process.hpp"

namespace brdfcl::test {

// `exe` (the CLI under test unless named) with `args`, run in `dir` under `o` (its cwd becomes dir).
inline RunResult runCli(const ScratchDir& dir, std::vector<std::string> args, ProcessOptions o = {},
                        const std::string& exe = BRDFCL_CLI_PATH) {
  args.insert(args.begin(), exe);
  o.cwd = dir.dir();
  return runProcess(std::move(args), dir.dir(), o);
}

inline void expectOneLineError(const RunResult& r, const std::string& text) {
  EXPECT_EQ(r.status, 2) << r.describe();
  ASSERT_EQ(r.errorLines().size(), 1u) << r.describe();
  EXPECT_NE(r.errorLines()[0].find(text), std::string::npos) << "expected '" << text << "' in\n" << r.describe();
}

}  // namespace brdfcl::test
