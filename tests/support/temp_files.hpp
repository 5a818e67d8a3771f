// Scratch files for tests: a path under the test temporary directory that no other test process uses, and a
// file written there.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace trionet::test {

/// A path for a scratch file called `name`, unique to this process.
inline std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "trionet-test-" + std::to_string(::getpid()) + "-" + name;
}

/// Writes `content` to a scratch file called `name`; its path.
inline std::string temp_file(const std::string& name, const std::string& content) {
  const std::string path = temp_path(name);
  std::ofstream(path, std::ios::binary) << content;
  return path;
}

}  // namespace trionet::test
