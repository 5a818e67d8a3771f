// The command line of the two-thread stress programs (tests/support/concurrency_stress.hpp and
// concurrency_stress_genius.hpp):
//
//   <program> [--steps N] [--seed S] [--node all|NODE[,NODE...]] [--link uart|dma]
//
// NODE is mc, keypad, can or genius. N is the link side's steps per node (default 2000000): with `--link uart`
// (the default) one received byte and one transmitted byte at most each, as a UART interrupt; with
// `--link dma` the ring nodes' link side takes runs of 1..8 bytes in bulk (receive, then transmit in bulk or a
// byte at a time), as a DMA-fed UART.
// For the Genius device N counts the characters on its bus (received, or its own read back); `--link` does
// not apply to it.
// Prints what each run did; returns 1 if any check failed, 2 on a bad command line.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "support/concurrency_stress.hpp"
#include "support/concurrency_stress_genius.hpp"

namespace trionet::stress {

// `--node`: "all", or node names separated by commas ("mc,keypad,can").
inline bool node_named(const std::string& which, const char* name) {
  return which == "all" || ("," + which + ",").find(std::string(",") + name + ",") != std::string::npos;
}
inline bool nodes_valid(const std::string& which) {
  if (which == "all") return true;
  std::string names = "," + which + ",";
  for (const char* name : {"mc", "keypad", "can", "genius"}) {
    const std::string token = std::string(",") + name + ",";
    for (std::size_t at; (at = names.find(token)) != std::string::npos;) names.erase(at, token.size() - 1);
  }
  return names == "," && !which.empty();
}

inline int command_line(const char* program, int argc, char** argv) {
  config cfg;
  cfg.link_steps = 2000000;
  std::string which = "all";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--steps") == 0) {
      cfg.link_steps = std::strtoull(argv[i + 1], nullptr, 10);
    } else if (std::strcmp(argv[i], "--seed") == 0) {
      cfg.seed = std::strtoull(argv[i + 1], nullptr, 10);
    } else if (std::strcmp(argv[i], "--node") == 0) {
      which = argv[i + 1];
    } else if (std::strcmp(argv[i], "--link") == 0 &&
               (std::strcmp(argv[i + 1], "uart") == 0 || std::strcmp(argv[i + 1], "dma") == 0)) {
      cfg.dma = std::strcmp(argv[i + 1], "dma") == 0;
    } else {
      argc = 0;
      break;
    }
  }
  if (argc % 2 == 0 || !nodes_valid(which)) {
    std::fprintf(stderr, "usage: %s [--steps N] [--seed S] [--node all|NODE[,NODE...]] [--link uart|dma]\n",
                 program);
    return 2;
  }
  bool ok = true;
  const auto show = [&](const char* name, const report& r) {
    std::printf("%-18s link side: %llu steps, %llu calls; program side: %llu calls; %llu messages in, %llu frames "
                "out (%llu own), %llu dropped whole (counted): %s\n",
                name, static_cast<unsigned long long>(r.link_steps), static_cast<unsigned long long>(r.link_calls),
                static_cast<unsigned long long>(r.program_calls), static_cast<unsigned long long>(r.messages_in),
                static_cast<unsigned long long>(r.frames_out), static_cast<unsigned long long>(r.own_frames),
                static_cast<unsigned long long>(r.dropped_whole), r.ok() ? "ok" : "FAILED");
    for (const std::string& f : r.failures) std::printf("  FAIL %s\n", f.c_str());
    ok = ok && r.ok();
    std::fflush(stdout);
  };
  if (node_named(which, "mc")) show("motion coordinator", run_motion_coordinator(cfg));
  if (node_named(which, "keypad")) show("keypad", run_keypad(cfg));
  if (node_named(which, "can")) show("CAN node", run_can(cfg));
  if (node_named(which, "genius")) show("Genius device", run_genius_device(cfg));
  std::printf("%s: %s\n", program, ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}

}  // namespace trionet::stress
