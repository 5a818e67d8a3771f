// The path of one received ring byte through a Motion Coordinator node, for callgrind: which of the library's
// files hold the code that one `receive(byte)` runs, for each kind of byte (a header, a data byte, an end of
// message) of a message the node forwards and of one it takes (delivers). scripts/bench runs
//   valgrind --tool=callgrind --collect-atstart=no --toggle-collect=trionet_measured_byte ...
//            trionet_ring_byte_path <kind>
// for each kind that `trionet_ring_byte_path --list` prints, and bench/report.py attributes the instructions
// to source files (inlined code to its own file), as for the other workloads.
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/vr.hpp"

namespace {

using mc_type = trionet::ring::motion_coordinator<>;

struct kind {
  const char* name;
  std::uint8_t hops;  // 3: forwarded (A - 1 = 2 passes on); 1: for the node
  int position;       // the byte measured: 0 header, 1 data, 3 end of message
};

constexpr kind kinds[] = {
    {"forwarded_header", 3, 0}, {"forwarded_data", 3, 2},  {"forwarded_end", 3, 3},
    {"delivered_header", 1, 0}, {"delivered_data", 1, 2}, {"delivered_end", 1, 3},
};

}  // namespace

// The one call measured: the node's byte entry point, as a UART interrupt calls it.
extern "C" [[gnu::noinline]] void trionet_measured_byte(mc_type& node, std::uint8_t byte) noexcept {
  node.receive(byte);
}

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--list") == 0) {
    for (const kind& k : kinds) std::printf("%s\n", k.name);
    return 0;
  }
  const kind* chosen = nullptr;
  for (const kind& k : kinds) {
    if (argc == 2 && std::strcmp(argv[1], k.name) == 0) chosen = &k;
  }
  if (chosen == nullptr) {
    std::fprintf(stderr, "usage: trionet_ring_byte_path --list | KIND\n");
    return 2;
  }
  static trionet::vr_table<1024, std::int64_t> vr;
  static mc_type node(vr);
  // A two-character message (a character transfer), warmed up three times (whole, then drained).
  const std::uint8_t message[] = {trionet::ring::make_header(chosen->hops, 1), 'O', 'K',
                                  trionet::ring::make_end_of_message(chosen->hops)};
  std::uint8_t out = 0;
  for (int round = 0; round < 3; ++round) {
    for (std::uint8_t b : message) node.receive(b);
    while (node.transmit(out)) {
    }
    while (node.get(4)) {
    }
  }
  for (int i = 0; i < chosen->position; ++i) node.receive(message[i]);
  trionet_measured_byte(node, message[chosen->position]);
  for (int i = chosen->position + 1; i < 4; ++i) node.receive(message[i]);
  std::size_t sent = 0;
  while (node.transmit(out)) ++sent;
  const auto counters = node.counters();
  const auto links = node.forwarding_counters();
  // The run did what it should: four messages forwarded (and sent on) or four taken.
  const bool ok = chosen->hops == 1 ? counters.character_messages == 4 && links.messages_forwarded == 0
                                    : links.messages_forwarded == 4 && sent == 4;
  std::printf("%s: byte 0x%02x, %s\n", chosen->name, message[chosen->position], ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
