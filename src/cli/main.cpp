// `trionet`: encode, decode, simulate and analyse Trio fibre-ring, TN20-17 CAN and Genius bus traffic
// (docs/cli.md). The parts and their command tables are in <part>_cli.cpp; cli.cpp dispatches.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <string>
#include <vector>

#include "cli.hpp"
#include "manual.hpp"

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
         "options. Every command takes --profile FILE (the wire parameters to use, docs/profile.md) and\n"
         "--fail-on-limit (a run a limit cut short exits 4, not 0). Options: --name value or --name=value.\n"
         "Exit status (docs/cli.md has it command by command): 0 done (wire errors are reported as\n"
         "events), 1 reading or writing failed or a live link was lost, 2 bad arguments, 3 a --check\n"
         "failed or a learn command found no single answer, 4 a limit cut the run short (--fail-on-limit).\n";
  return out;
}

}  // namespace

namespace {

int run(const std::vector<std::string>& words) {
  if (words.empty()) {
    std::fputs(("trionet: a part is needed: ring, can, genius or profile\n" + usage()).c_str(), stderr);
    return trionet::cli::exit_usage;
  }
  if (words[0] == "--help" || words[0] == "-h" || words[0] == "help") {
    trionet::cli::write_stdout(usage());
    return trionet::cli::exit_ok;
  }
  // The man pages and the completion script, written from the command tables (manual.hpp).
  const trionet::cli::part_list all{parts, sizeof parts / sizeof parts[0]};
  if (words[0] == "--man" && words.size() <= 2) {
    std::string page = trionet::cli::manual_page_names(all);
    if (words.size() == 2 && !trionet::cli::manual_page(all, words[1], page))
    {
      std::string names = trionet::cli::manual_page_names(all);
      names.pop_back();
      for (char& c : names) c = c == '\n' ? ' ' : c;
      return trionet::cli::fail("no man page '" + trionet::host::printable(words[1]) + "' (expected one of: " + names +
                                ")");
    }
    std::fputs(page.c_str(), stdout);
    return std::fflush(stdout) == 0 ? trionet::cli::exit_ok : trionet::cli::fail_io("cannot write standard output");
  }
  if (words[0] == "--completion") {
    if (words.size() != 2 || words[1] != "bash") return trionet::cli::fail("--completion takes one shell: bash");
    std::fputs(trionet::cli::bash_completion(all).c_str(), stdout);
    return std::fflush(stdout) == 0 ? trionet::cli::exit_ok : trionet::cli::fail_io("cannot write standard output");
  }
  if (words[0] == "--version") {
    trionet::cli::write_stdout(trionet::cli::version_line() + "\n");
    return trionet::cli::exit_ok;
  }
  for (const part* p : parts) {
    if (words[0] == p->name) return trionet::cli::dispatch(*p, std::vector<std::string>(words.begin() + 1, words.end()));
  }
  return trionet::cli::fail("unknown part '" + trionet::host::printable(words[0]) + "' (expected ring, can, genius or profile)");
}

}  // namespace

namespace {

// A standard stream the tool was started without (`>&-`) is held by /dev/null opened the other way, so that
// using it fails as on a closed descriptor (EBADF) and no file the command opens takes its number: a capture
// file opened as descriptor 1 would otherwise receive the tool's output.
void hold_closed_standard_streams() {
  for (int fd = 0; fd <= 2; ++fd) {
    if (fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    const int held = open("/dev/null", fd == 0 ? O_WRONLY : O_RDONLY);
    if (held > fd) close(held);  // cannot happen: 0..fd-1 are open, so open() takes fd
  }
}

}  // namespace

int main(int argc, char** argv) {
  hold_closed_standard_streams();
  // A closed output is an error a command reports (EPIPE from write), not a silent death by SIGPIPE.
  std::signal(SIGPIPE, SIG_IGN);
  return trionet::cli::finish_output(run(std::vector<std::string>(argv + 1, argv + argc)));
}
