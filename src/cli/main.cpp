// `trionet`: encode, decode, simulate and analyse Trio fibre-ring, TN20-17 CAN and Genius bus traffic
// (docs/cli.md). The parts and their command tables are in <part>_cli.cpp; cli.cpp dispatches.
#include <cstdio>
#include <string>
#include <vector>

#include "cli.hpp"

namespace {

using trionet::cli::part;

const part* const parts[] = {&trionet::cli::ring_part, &trionet::cli::can_part, &trionet::cli::genius_part,
                             &trionet::cli::profile_part};

std::string usage() {
  std::string out = "usage: trionet <part> <command> [options]\n       trionet --version\n\nparts:\n";
  for (const part* p : parts) {
    std::string name = p->name;
    name.resize(8, ' ');
    out += "  " + name + " " + p->summary + "\n";
  }
  out += "\nRun `trionet <part> --help` for a part's commands, `trionet <part> <command> --help` for a command's\n"
         "options. Every command takes --profile FILE: the wire parameters to use (docs/profile.md).\n"
         "Exit status: 0 the input was read (wire errors are reported as events), 1 reading or\n"
         "writing failed, 2 bad arguments, 3 a --check failed or a learn command found no single answer.\n";
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> words(argv + 1, argv + argc);
  if (words.empty()) {
    std::fputs(("trionet: a part is needed: ring, can, genius or profile\n" + usage()).c_str(), stderr);
    return trionet::cli::exit_usage;
  }
  if (words[0] == "--help" || words[0] == "-h" || words[0] == "help") {
    std::fputs(usage().c_str(), stdout);
    return trionet::cli::exit_ok;
  }
  if (words[0] == "--version") {
    std::printf("%s\n", trionet::cli::version_line().c_str());
    return trionet::cli::exit_ok;
  }
  for (const part* p : parts) {
    if (words[0] == p->name) return trionet::cli::dispatch(*p, std::vector<std::string>(words.begin() + 1, words.end()));
  }
  return trionet::cli::fail("unknown part '" + trionet::host::printable(words[0]) + "' (expected ring, can, genius or profile)");
}
