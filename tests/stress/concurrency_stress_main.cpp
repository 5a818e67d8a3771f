// trionet_concurrency_stress: the two sides of a node run in two threads with no lock and no interrupt
// masking (tests/support/concurrency_stress.hpp). scripts/concurrency-test builds it with ThreadSanitizer.
//
//   trionet_concurrency_stress [--steps N] [--seed S] [--node mc|keypad|can|all]
//
// N is the link side's steps per node (one received byte and one transmitted byte at most each; default
// 2000000). Prints what each run did; exits 1 if any check failed.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "support/concurrency_stress.hpp"

namespace stress = trionet::stress;

int main(int argc, char** argv) {
  stress::config cfg;
  cfg.link_steps = 2000000;
  std::string which = "all";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--steps") == 0) {
      cfg.link_steps = std::strtoull(argv[i + 1], nullptr, 10);
    } else if (std::strcmp(argv[i], "--seed") == 0) {
      cfg.seed = std::strtoull(argv[i + 1], nullptr, 10);
    } else if (std::strcmp(argv[i], "--node") == 0) {
      which = argv[i + 1];
    } else {
      argc = 0;
      break;
    }
  }
  if (argc % 2 == 0 || (which != "all" && which != "mc" && which != "keypad" && which != "can")) {
    std::fprintf(stderr, "usage: trionet_concurrency_stress [--steps N] [--seed S] [--node mc|keypad|can|all]\n");
    return 2;
  }
  bool ok = true;
  const auto show = [&](const char* name, const stress::report& r) {
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
  if (which == "all" || which == "mc") show("motion coordinator", stress::run_motion_coordinator(cfg));
  if (which == "all" || which == "keypad") show("keypad", stress::run_keypad(cfg));
  if (which == "all" || which == "can") show("CAN node", stress::run_can(cfg));
  std::printf("trionet_concurrency_stress: %s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
