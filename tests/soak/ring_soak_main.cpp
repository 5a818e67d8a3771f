// trionet_ring_soak: the fault-injection soak of the fibre ring (tests/support/ring_soak.hpp) over every
// configuration kind, with a table of what became of every message.
//
//   trionet_ring_soak [--episodes N] [--seed S]
//
// Rings of 2..15 nodes (Motion Coordinators and keypads in network mode); on every link, bit flips or
// dropped bytes at 1e-4, 1e-3 and 1e-2 per byte, or one cut of 10, 100 or 1000 byte-times per episode.
// Exits 1 if any episode wedged or livelocked, any VR was written wrongly, or any loss went uncounted that
// the protocol would let a node see.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "support/ring_soak.hpp"

namespace soak = trionet::soak;

int main(int argc, char** argv) {
  std::uint32_t episodes = 40;
  std::uint64_t seed = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--episodes") == 0) {
      episodes = static_cast<std::uint32_t>(std::strtoul(argv[i + 1], nullptr, 10));
    } else if (std::strcmp(argv[i], "--seed") == 0) {
      seed = std::strtoull(argv[i + 1], nullptr, 10);
    } else {
      std::fprintf(stderr, "usage: trionet_ring_soak [--episodes N] [--seed S]\n");
      return 2;
    }
  }
  if (argc % 2 == 0) {
    std::fprintf(stderr, "usage: trionet_ring_soak [--episodes N] [--seed S]\n");
    return 2;
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
  std::printf("| ring | faults | episodes | sent | intact | corrupted (no CRC) | misdelivered | lost, counted | "
              "lost, vanished | lost, merged | lost, unexplained | wrong VR writes | wedged | livelocked | "
              "open messages ended (median / max) | damage cleared (median / max) | probes done (median / max) | "
              "bound |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---:|\n");
  bool ok = true;
  soak::report total;
  std::uint64_t worst_cleared = 0, worst_probes = 0, worst_open = 0;
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
      const soak::report r = soak::run(cfg);
      char what[32];
      if (f.kind == soak::fault_kind::cut) {
        std::snprintf(what, sizeof what, "cut %u", f.cut);
      } else {
        std::snprintf(what, sizeof what, "%s %.0e", to_string(f.kind), f.rate);
      }
      std::printf("| %zu (%zu keypads) | %s | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | %llu | "
                  "%llu | %llu | %llu / %llu | %llu / %llu | %llu / %llu | %llu |\n",
                  shape.nodes, shape.keypads, what, static_cast<unsigned long long>(r.episodes),
                  static_cast<unsigned long long>(r.sent), static_cast<unsigned long long>(r.delivered_intact),
                  static_cast<unsigned long long>(r.delivered_corrupted),
                  static_cast<unsigned long long>(r.misdelivered), static_cast<unsigned long long>(r.lost_counted),
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
      if (r.wedged + r.livelocked + r.wrong_vr_writes + r.lost_unexplained + r.untracked_headers != 0 ||
          r.probes_delivered != r.probes) {
        ok = false;
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
      total.lost_counted += r.lost_counted;
      total.lost_vanished += r.lost_vanished;
      total.lost_merged += r.lost_merged;
      total.lost_unexplained += r.lost_unexplained;
      total.wrong_vr_writes += r.wrong_vr_writes;
      total.wedged += r.wedged;
      total.livelocked += r.livelocked;
      total.episodes += r.episodes;
      total.faults += r.faults;
      worst_cleared = std::max(worst_cleared, soak::maximum(r.damage_cleared));
      worst_open = std::max(worst_open, soak::maximum(r.open_closed));
      worst_probes = std::max(worst_probes, soak::maximum(r.probes_done));
    }
  }
  std::printf("\nall: %llu episodes, %llu faults, %llu messages sent: %llu intact, %llu corrupted (no CRC), "
              "%llu misdelivered, lost %llu counted + %llu vanished + %llu merged + %llu unexplained; "
              "%llu wrong VR writes, %llu wedged, %llu livelocked; messages open at the last fault ended within "
              "%llu byte-times, damage cleared within %llu, probes done within %llu\n",
              static_cast<unsigned long long>(total.episodes), static_cast<unsigned long long>(total.faults),
              static_cast<unsigned long long>(total.sent), static_cast<unsigned long long>(total.delivered_intact),
              static_cast<unsigned long long>(total.delivered_corrupted),
              static_cast<unsigned long long>(total.misdelivered), static_cast<unsigned long long>(total.lost_counted),
              static_cast<unsigned long long>(total.lost_vanished), static_cast<unsigned long long>(total.lost_merged),
              static_cast<unsigned long long>(total.lost_unexplained),
              static_cast<unsigned long long>(total.wrong_vr_writes), static_cast<unsigned long long>(total.wedged),
              static_cast<unsigned long long>(total.livelocked), static_cast<unsigned long long>(worst_open),
              static_cast<unsigned long long>(worst_cleared),
              static_cast<unsigned long long>(worst_probes));
  return ok ? 0 : 1;
}
