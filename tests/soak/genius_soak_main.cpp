// trionet_genius_soak: the fault-injection soak of a Genius bus of device nodes (src/sim/genius_soak.hpp):
// rounds of a random layout planned without collision risk, clean scans, random faults (noise bursts, a device
// stopping mid-transmission, a device powered off and on, a cut bus segment), clean scans again.
//
//   trionet_genius_soak [--rounds N] [--seed S] [--faults F]
//
// Prints what happened and every check; exits 1 if a scan wedged after recovery, a device never took its turn
// again (or took more than twice one scan plus the idle time, or later than the run of characters under way and
// the collisions after the faults explain), a loss went uncounted, or more deliveries
// escaped their CRC-6 than the 1-in-64 expectation's 99.9 % bound allows; 2 on a bad command line.
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "genius_soak.hpp"

int main(int argc, char** argv) {
  trionet::host::genius_soak_config config;
  config.rounds = 40;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--rounds") == 0 && i + 1 < argc) {
      config.rounds = static_cast<std::uint32_t>(std::strtoul(argv[++i], nullptr, 10));
    } else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
      config.seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (std::strcmp(argv[i], "--faults") == 0 && i + 1 < argc) {
      config.faults_per_round = static_cast<std::uint32_t>(std::strtoul(argv[++i], nullptr, 10));
    } else {
      std::fprintf(stderr, "usage: trionet_genius_soak [--rounds N] [--seed S] [--faults F]\n");
      return 2;
    }
  }
  const trionet::host::genius_soak_report r = trionet::host::run_genius_soak(config);
  const auto u = [](std::uint64_t v) { return static_cast<unsigned long long>(v); };
  std::printf("genius soak, seed %llu: %u rounds, %.3f s of bus time\n", u(config.seed), r.rounds, r.simulated_s);
  std::printf("faults: %llu noise bursts, %llu power cycles, %llu stopped mid-transmission, %llu cuts\n", u(r.faults[0]),
              u(r.faults[1]), u(r.faults[2]), u(r.faults[3]));
  std::printf("traffic: %llu transmissions, %llu deliveries; %llu collisions, %llu framing errors, %llu CRC errors, "
              "%llu lost transmissions, %llu idle restarts\n",
              u(r.transmissions), u(r.deliveries), u(r.collisions), u(r.framing_errors), u(r.crc_errors),
              u(r.lost_transmissions), u(r.idle_restarts));
  std::printf("recovery: %llu devices measured, %llu later than one scan + the idle time (worst %.3f x), %llu later "
              "than twice that or never\n",
              u(r.recoveries), u(r.late_recoveries), r.worst_recovery_ratio, u(r.lost_recoveries));
  std::printf("late recoveries explained: %llu by the run of characters under way (a UART out of step until a "
              "silence of a character time), %llu by a collision once the faults stopped (+ the idle time); %llu "
              "unexplained (worst %.3f x that bound)\n",
              u(r.late_out_of_step), u(r.late_after_collision), u(r.late_unexplained), r.worst_implied_ratio);
  std::printf("wedged scans after recovery: %llu\n", u(r.wedged_scans));
  std::printf("losses: %llu (transmission, listener) pairs checked, %llu neither heard nor counted\n",
              u(r.losses_checked), u(r.losses_uncounted));
  std::printf("CRC-6 escapes: %llu of %llu corrupted transmissions that reached a CRC-6 check (expected %.2f, 99.9 %% "
              "bound %llu); deliveries with bytes not sent %llu, with the right bytes and a wrong sender or kind "
              "%llu\n",
              u(r.escape_events), u(r.corrupt_events), r.expected_escapes, u(r.escape_bound), u(r.wrong_data),
              u(r.wrong_header));
  for (const std::string& note : r.notes) std::printf("  late: %s\n", note.c_str());
  for (const std::string& failure : r.failures) std::printf("  FAIL %s\n", failure.c_str());
  std::printf("trionet_genius_soak: %s\n", r.ok() ? "PASS" : "FAIL");
  return r.ok() ? 0 : 1;
}
