// `trionet`: encode, decode, simulate and analyse Trio fibre-ring, TN20-17 CAN and Genius bus traffic.
#include <cstdio>
#include <string>
#include <vector>

#include "cli.hpp"

namespace {

constexpr const char* usage_text =
    "usage: trionet <part> <command> [options]\n"
    "\n"
    "parts:\n"
    "  ring     Trio Motion Coordinator fibre-optic ring (encode, decode, simulate)\n"
    "  can      Trio TN20-17 CANbus VR exchange (encode, decode, table)\n"
    "  genius   GE Genius bus (encode, decode, timing)\n"
    "\n"
    "Run `trionet <part> --help` for a part's commands.\n";

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> words(argv + 1, argv + argc);
  if (words.empty() || words[0] == "--help" || words[0] == "-h" || words[0] == "help") {
    std::fputs(usage_text, words.empty() ? stderr : stdout);
    return words.empty() ? trionet::cli::exit_usage : trionet::cli::exit_ok;
  }
  const std::string part = words[0];
  words.erase(words.begin());
  if (part == "ring") return trionet::cli::ring_main(words);
  if (part == "can") return trionet::cli::can_main(words);
  if (part == "genius") return trionet::cli::genius_main(words);
  return trionet::cli::fail("unknown part '" + part + "' (expected ring, can or genius)");
}
