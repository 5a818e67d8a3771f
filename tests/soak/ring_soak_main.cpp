// trionet_ring_soak: the fault-injection soak of the fibre ring (tests/support/ring_soak.hpp) over every
// configuration kind, with a table of what became of every message.
//
//   trionet_ring_soak [--episodes N] [--seed S] [--accept-all-vrs]
//
// Rings of 2..15 nodes (Motion Coordinators and keypads in network mode); on every link, bit flips or
// dropped bytes at 1e-4, 1e-3 and 1e-2 per byte, or one cut of 10, 100 or 1000 byte-times per episode.
// Each MC's VR write policy accepts only the VRs it owns, so that a direct variable transfer taken at the
// wrong node is refused and counted; --accept-all-vrs gives every MC the library's default policy instead
// (the same traffic and faults: what that policy would have written wrongly).
// Exits 1 if any episode wedged or livelocked, any VR was written wrongly, or any loss went uncounted that
// the protocol would let a node see.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <string>
#include <vector>

#include "support/ring_soak.hpp"
#include "trionet/host/progress.hpp"

namespace soak = trionet::soak;

int main(int argc, char** argv) {
  std::uint32_t episodes = 40;
  std::uint64_t seed = 1;
  bool accept_all_vrs = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--episodes") == 0 && i + 1 < argc) {
      episodes = static_cast<std::uint32_t>(std::strtoul(argv[++i], nullptr, 10));
    } else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (std::strcmp(argv[i], "--accept-all-vrs") == 0) {
      accept_all_vrs = true;
    } else {
      std::fprintf(stderr, "usage: trionet_ring_soak [--episodes N] [--seed S] [--accept-all-vrs]\n");
      return 2;
    }
  }
  struct ring_shape {
    std::size_t nodes, keypads;
  };
  const ring_shape shapes[] = {{2, 0}, {3, 1}, {5, 1}, {8, 2}, {15, 4}};
  struct fault {
    soak::fault_kind kind;
    double rate;
    std::uint32_t cut;
  };
  const fault faults[] = {{soak::fault_kind::flip, 1e-4, 0}, {soak::fault_kind::flip, 1e-3, 0},
                          {soak::fault_kind::flip, 1e-2, 0}, {soak::fault_kind::drop, 1e-4, 0},
                          {soak::fault_kind::drop, 1e-3, 0}, {soak::fault_kind::drop, 1e-2, 0},
                          {soak::fault_kind::cut, 0, 10},    {soak::fault_kind::cut, 0, 100},
                          {soak::fault_kind::cut, 0, 1000}};
  std::printf("| ring | faults | episodes | sent | intact | corrupted (no CRC) | misdelivered | misaddressed, "
              "refused | lost, counted | lost, vanished | lost, merged | lost, unexplained | wrong VR writes | "
              "wedged | livelocked | open messages ended (median / max) | damage cleared (median / max) | "
              "probes done (median / max) | bound |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---:|\n");
  bool ok = true;
  soak::report total;
  // On a terminal, the configurations done, the rate and the time left on standard error.
  trionet::host::progress shown("trionet_ring_soak", "configurations",
                                static_cast<double>(std::size(shapes) * std::size(faults)));
  double done = 0;
  for (const ring_shape& shape : shapes) {
    for (const fault& f : faults) {
      soak::config cfg;
      cfg.nodes = shape.nodes;
      cfg.keypads = shape.keypads;
      cfg.kind = f.kind;
      cfg.rate = f.rate;
      cfg.cut_length = f.cut;
      cfg.episodes = episodes;
      cfg.fault_byte_times = f.cut == 1000 ? 2500 : 1500;
      cfg.seed = seed++;
      cfg.accept_all_vrs = accept_all_vrs;
      const soak::report r = soak::run(cfg);
      shown.clear();
      char what[32];
      if (f.kind == soak::fault_kind::cut) {
        std::snprintf(what, sizeof what, "cut %u", f.cut);
      } else {
        std::snprintf(what, sizeof what, "%s %.0e", to_string(f.kind), f.rate);
      }
      std::printf("| %zu (%zu keypads) | %s | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | "
                  "%llu | %llu | %llu | %llu / %llu | %llu / %llu | %llu / %llu | %llu |\n",
                  shape.nodes, shape.keypads, what, static_cast<unsigned long long>(r.episodes),
                  static_cast<unsigned long long>(r.sent), static_cast<unsigned long long>(r.delivered_intact),
                  static_cast<unsigned long long>(r.delivered_corrupted),
                  static_cast<unsigned long long>(r.misdelivered),
                  static_cast<unsigned long long>(r.misaddressed_refused),
                  static_cast<unsigned long long>(r.lost_counted),
                  static_cast<unsigned long long>(r.lost_vanished), static_cast<unsigned long long>(r.lost_merged),
                  static_cast<unsigned long long>(r.lost_unexplained),
                  static_cast<unsigned long long>(r.wrong_vr_writes), static_cast<unsigned long long>(r.wedged),
                  static_cast<unsigned long long>(r.livelocked),
                  static_cast<unsigned long long>(soak::median(r.open_closed)),
                  static_cast<unsigned long long>(soak::maximum(r.open_closed)),
                  static_cast<unsigned long long>(soak::median(r.damage_cleared)),
                  static_cast<unsigned long long>(soak::maximum(r.damage_cleared)),
                  static_cast<unsigned long long>(soak::median(r.probes_done)),
                  static_cast<unsigned long long>(soak::maximum(r.probes_done)),
                  static_cast<unsigned long long>(soak::recovery_bound(shape.nodes)));
      std::fflush(stdout);
      shown.update(++done);
      if (r.wedged + r.livelocked + r.wrong_vr_writes + r.owned_refused + r.lost_unexplained +
                  r.untracked_headers !=
              0 ||
          r.probes_delivered != r.probes || r.fates() != r.sent) {
        ok = false;
        // Every wrong VR write, and the first problem if it is another.
        for (const std::string& w : r.wrong_writes) std::fprintf(stderr, "trionet_ring_soak: %s\n", w.c_str());
        if (r.wrong_writes.empty() || r.first_problem.find("wrong VR write") == std::string::npos)
          std::fprintf(stderr, "trionet_ring_soak: %s\n", r.first_problem.c_str());
      }
      if (std::max(soak::maximum(r.damage_cleared), soak::maximum(r.open_closed)) >
          soak::recovery_bound(shape.nodes)) {
        ok = false;
        std::fprintf(stderr, "trionet_ring_soak: %zu nodes, %s: damage cleared after %llu byte-times, bound %llu\n",
                     shape.nodes, what, static_cast<unsigned long long>(soak::maximum(r.damage_cleared)),
                     static_cast<unsigned long long>(soak::recovery_bound(shape.nodes)));
      }
      total.sent += r.sent;
      total.delivered_intact += r.delivered_intact;
      total.delivered_corrupted += r.delivered_corrupted;
      total.misdelivered += r.misdelivered;
      total.misaddressed_refused += r.misaddressed_refused;
      total.corrupted_refused += r.corrupted_refused;
      total.owned_refused += r.owned_refused;
      total.lost_counted += r.lost_counted;
      total.lost_vanished += r.lost_vanished;
      total.lost_merged += r.lost_merged;
      total.lost_unexplained += r.lost_unexplained;
      total.wrong_vr_writes += r.wrong_vr_writes;
      total.wrong_vr_misaddressed += r.wrong_vr_misaddressed;
      total.wrong_vr_crc_missed += r.wrong_vr_crc_missed;
      total.wrong_vr_no_message += r.wrong_vr_no_message;
      total.wedged += r.wedged;
      total.livelocked += r.livelocked;
      total.episodes += r.episodes;
      total.probes += r.probes;
      total.probes_delivered += r.probes_delivered;
      total.faults += r.faults;
      total.open_closed.insert(total.open_closed.end(), r.open_closed.begin(), r.open_closed.end());
      total.damage_cleared.insert(total.damage_cleared.end(), r.damage_cleared.begin(), r.damage_cleared.end());
      total.probes_done.insert(total.probes_done.end(), r.probes_done.begin(), r.probes_done.end());
    }
  }
  shown.finish();
  std::printf("\nall (VR write policy: %s): %llu episodes, %llu faults, %llu messages sent: %llu intact, "
              "%llu corrupted (no CRC), %llu misdelivered, %llu misaddressed and refused by the write policy, "
              "lost %llu counted + %llu vanished + %llu merged + %llu unexplained; %llu wrong VR writes "
              "(%llu misaddressed, %llu CRC missed, %llu from no message), %llu refused writes whose CRC missed "
              "a corruption, %llu refused to their own destination; %llu wedged, %llu livelocked; %llu of %llu "
              "probes delivered intact; byte-times (median / max over the episodes): messages open at the last "
              "fault ended %llu / %llu, damage cleared %llu / %llu, probes done %llu / %llu\n",
              accept_all_vrs ? "every VR" : "owned VRs only", static_cast<unsigned long long>(total.episodes),
              static_cast<unsigned long long>(total.faults), static_cast<unsigned long long>(total.sent),
              static_cast<unsigned long long>(total.delivered_intact),
              static_cast<unsigned long long>(total.delivered_corrupted),
              static_cast<unsigned long long>(total.misdelivered),
              static_cast<unsigned long long>(total.misaddressed_refused),
              static_cast<unsigned long long>(total.lost_counted), static_cast<unsigned long long>(total.lost_vanished),
              static_cast<unsigned long long>(total.lost_merged), static_cast<unsigned long long>(total.lost_unexplained),
              static_cast<unsigned long long>(total.wrong_vr_writes),
              static_cast<unsigned long long>(total.wrong_vr_misaddressed),
              static_cast<unsigned long long>(total.wrong_vr_crc_missed),
              static_cast<unsigned long long>(total.wrong_vr_no_message),
              static_cast<unsigned long long>(total.corrupted_refused),
              static_cast<unsigned long long>(total.owned_refused), static_cast<unsigned long long>(total.wedged),
              static_cast<unsigned long long>(total.livelocked), static_cast<unsigned long long>(total.probes_delivered),
              static_cast<unsigned long long>(total.probes),
              static_cast<unsigned long long>(soak::median(total.open_closed)),
              static_cast<unsigned long long>(soak::maximum(total.open_closed)),
              static_cast<unsigned long long>(soak::median(total.damage_cleared)),
              static_cast<unsigned long long>(soak::maximum(total.damage_cleared)),
              static_cast<unsigned long long>(soak::median(total.probes_done)),
              static_cast<unsigned long long>(soak::maximum(total.probes_done)));
  return ok ? 0 : 1;
}
