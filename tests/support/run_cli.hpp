// Runs the built `trionet` tool for CLI tests and captures its stdout, stderr and exit code.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace trionet::test {

struct cli_result {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream all;
  all << in.rdbuf();
  return all.str();
}

/// Runs `trionet <args>` through the shell, feeding `input` on stdin. `args` is shell text.
inline cli_result run_cli(const std::string& args, const std::string& input = "") {
  const std::string base = "/tmp/trionet-cli-" + std::to_string(::getpid());
  const std::string in_path = base + ".in", out_path = base + ".out", err_path = base + ".err";
  {
    std::ofstream in(in_path, std::ios::binary);
    in << input;
  }
  const std::string command =
      std::string(TRIONET_CLI_PATH) + " " + args + " <" + in_path + " >" + out_path + " 2>" + err_path;
  const int status = std::system(command.c_str());
  cli_result result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(out_path);
  result.err = slurp(err_path);
  std::remove(in_path.c_str());
  std::remove(out_path.c_str());
  std::remove(err_path.c_str());
  return result;
}

/// `trionet <args>` through the shell, where `args` may redirect standard input or output itself
/// (`>/dev/full`, `</dev/zero`); what it does not redirect comes from `input` and goes to `out`.
inline cli_result run_cli_redirected(const std::string& args, const std::string& input = "") {
  const std::string base = "/tmp/trionet-cli-redirected-" + std::to_string(::getpid());
  const std::string in_path = base + ".in", out_path = base + ".out", err_path = base + ".err";
  {
    std::ofstream in(in_path, std::ios::binary);
    in << input;
  }
  std::string command = std::string(TRIONET_CLI_PATH) + " " + args;
  if (args.find('<') == std::string::npos) command += " <" + in_path;
  if (args.find('>') == std::string::npos) command += " >" + out_path;
  command += " 2>" + err_path;
  const int status = std::system(command.c_str());
  cli_result result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(out_path);
  result.err = slurp(err_path);
  for (const std::string& path : {in_path, out_path, err_path}) std::remove(path.c_str());
  return result;
}

/// A usage error: exit status 2, nothing on stdout, and on stderr a "trionet: " message that mentions
/// `mentions` (when given).
inline void expect_usage_error(const std::string& args, const std::string& mentions = "",
                               const std::string& input = "") {
  const cli_result r = run_cli(args, input);
  EXPECT_EQ(r.exit_code, 2) << args;
  EXPECT_EQ(r.out, "") << args;
  EXPECT_EQ(r.err.rfind("trionet: ", 0), 0u) << args << ": " << r.err;
  EXPECT_NE(r.err.find(mentions), std::string::npos) << args << ": " << r.err;
}

/// A failure to read or write (a missing file or port, a closed output): exit status 1, nothing on stdout,
/// and on stderr exactly one line, a "trionet: " message that mentions `mentions` (when given).
inline void expect_io_error(const std::string& args, const std::string& mentions = "", const std::string& input = "") {
  const cli_result r = run_cli_redirected(args, input);
  EXPECT_EQ(r.exit_code, 1) << args;
  EXPECT_EQ(r.out, "") << args;
  EXPECT_EQ(r.err.rfind("trionet: ", 0), 0u) << args << ": " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  EXPECT_NE(r.err.find(mentions), std::string::npos) << args << ": " << r.err;
}

}  // namespace trionet::test
