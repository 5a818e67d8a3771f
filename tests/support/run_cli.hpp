// Runs the built `trionet` tool for CLI tests and captures its stdout, stderr and exit code.
#pragma once

#include <sys/wait.h>

#include <unistd.h>
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

}  // namespace trionet::test
