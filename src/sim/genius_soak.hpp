// The fault-injection soak of a Genius bus of devices (docs/genius.md, "Soak"): round after round, a random
// layout planned without collision risk (genius_plan.hpp) runs clean, then through random faults (noise
// bursts, a device stopping mid-transmission, a device powered off and on, a cut bus segment), then clean
// again. Checked in every round, once the faults stop:
//   - recovery: every device that sends takes its turn again (a whole transmission) within one scan plus the
//     idle time (32 skip times + 2 character times), plus what is left of a transmission under way, of the
//     moment the last fault ended. Measured and reported; above twice that is a failure. A later recovery is
//     explained only by what the device rules imply (docs/genius.md, "Soak"): the rest of the run of
//     back-to-back characters under way (a UART out of step until a silence of a character time), and a
//     collision once the faults stopped plus the idle time after it; anything later is a failure;
//   - no wedged scan: after that, every scan holds a whole transmission from every device that sends;
//   - every loss counted: a whole transmission that reached a listening device is heard by it, or the device
//     counts an error while it passes;
//   - CRC-6 escapes: deliveries that passed their CRC-6 but carry bytes their sender did not send, against
//     the 1-in-64 expectation (a 99.9 % binomial bound over the corrupted transmissions that reached a CRC
//     check, each counted once: devices that sample one corrupted signal see the same corruption). Deliveries whose sender or kind is wrong but whose bytes are right (the SBAs in control
//     characters are covered by no CRC, docs/protocol.md 3.2) are counted apart.
//
// Host side (heap).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace trionet::host {

struct genius_soak_config {
  std::uint64_t seed = 1;
  std::uint32_t rounds = 20;
  std::uint32_t faults_per_round = 6;
  std::uint32_t clean_scans = 8;  ///< before the faults, and after them
};

struct genius_soak_report {
  std::uint32_t rounds = 0;
  std::uint64_t faults[4] = {};  ///< by genius_fault_kind: noise, power_off, stop, cut
  std::uint64_t transmissions = 0;
  std::uint64_t deliveries = 0;
  std::uint64_t crc_errors = 0;
  std::uint64_t framing_errors = 0;
  std::uint64_t lost_transmissions = 0;
  std::uint64_t collisions = 0;
  std::uint64_t idle_restarts = 0;
  std::uint64_t losses_checked = 0;   ///< (transmission, listener) pairs checked
  std::uint64_t losses_uncounted = 0;
  std::uint64_t wedged_scans = 0;
  std::uint64_t late_recoveries = 0;  ///< devices that took longer than one scan + the idle time (+ the
                                      ///< transmission under way when the faults stopped)
  std::uint64_t late_out_of_step = 0;      ///< of the late: within one scan + the idle time + the run of
                                          ///< characters under way (a UART out of step until a silence)
  std::uint64_t late_after_collision = 0;  ///< of the late: a collision once the faults stopped, plus the idle
                                          ///< time it costs
  std::uint64_t late_unexplained = 0;      ///< of the late: neither (a failure)
  double worst_implied_ratio = 0;          ///< worst recovery / the bound with those allowances
  std::uint64_t lost_recoveries = 0;  ///< devices that took more than twice that, or never sent again
  std::uint64_t recoveries = 0;       ///< devices whose recovery was measured
  double worst_recovery_ratio = 0;    ///< worst recovery / that bound
  std::uint64_t wrong_data = 0;       ///< deliveries with bytes the sender did not send (CRC-6 escapes)
  std::uint64_t wrong_header = 0;     ///< deliveries with the right bytes but the wrong sender or kind
  std::uint64_t crc_checked_corrupt = 0;  ///< device checks of corrupted transmissions (CRC errors + wrong_data)
  std::uint64_t corrupt_events = 0;   ///< corrupted transmissions that reached a CRC-6 check, each once
  std::uint64_t escape_events = 0;    ///< of which some device delivered with bytes not sent
  double expected_escapes = 0;        ///< corrupt_events / 64
  std::uint64_t escape_bound = 0;     ///< 99.9 % binomial upper bound over corrupt_events
  double simulated_s = 0;
  std::vector<std::string> failures;  ///< what went wrong, by round (at most 20)
  /// The soak's verdict: late recoveries (above 1x, up to 2x the bound) that the run under way or a collision
  /// explain are reported, not failures.
  bool ok() const { return failures.empty() && losses_uncounted == 0 && wedged_scans == 0 && lost_recoveries == 0 &&
                           late_unexplained == 0 && escape_events <= escape_bound; }
  std::vector<std::string> notes;     ///< late recoveries, described (at most 20)
};

/// Runs the soak; `progress(round, report)` (optional) after each round.
genius_soak_report run_genius_soak(const genius_soak_config& config,
                                   const std::function<void(std::uint32_t, const genius_soak_report&)>& progress = {});

/// The smallest k with P(X > k) < 1 - confidence for X ~ Binomial(n, p).
std::uint64_t binomial_upper_bound(std::uint64_t n, double p, double confidence);

}  // namespace trionet::host
