// A deterministic fibre-ring simulator for tests, examples and tools.
//
//   node 0 --link 0--> node 1 --link 1--> ... node n-1 --link n-1--> node 0
//
// Time advances in byte-times. In each step every node, in order, is asked for one byte to transmit; then
// every byte that went onto a link is delivered to the next node; then every node whose incoming link has
// now carried no byte for `idle_byte_times` (docs/protocol.md 1.10, default 2) while it has a message open is told
// that its line is idle, as a UART's idle-line interrupt would. So a byte takes one byte-time per link, a
// forwarded byte one byte-time per node, and the same inputs always give the same run.
// Faults can be injected per link: drop the next byte, flip bits of the next byte, cut the link, or a hook
// that decides for every byte on every link.
//
// The caller owns the nodes (any `byte_port`: Motion Coordinators, keypads, or its own). No heap: the
// trace goes to a callback the caller supplies. Cost: MaxNodes pointers and faults; O(nodes) per step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "trionet/transport.hpp"

namespace trionet::ring {

/// One byte on one link, as the trace callback sees it.
struct link_byte {
  std::uint64_t time;     ///< the byte-time it was sent in
  std::size_t link;       ///< link i runs from node i to node (i + 1) mod n
  std::uint8_t sent;      ///< the byte the transmitter sent
  std::uint8_t received;  ///< the byte the receiver got (differs when bits were flipped)
  bool delivered;         ///< false when the byte was dropped or the link is cut
};

/// The receiver of a link was told that its line is idle while it had a message open (docs/protocol.md 1.10).
/// A trace callback that also accepts this type sees these events.
struct line_idle_event {
  std::uint64_t time;  ///< the byte-time at whose end it happened
  std::size_t link;    ///< the idle link; its receiver is node (link + 1) mod n
};

/// What a fault hook does to one byte on a link.
struct byte_fault {
  bool drop = false;           ///< the byte never arrives
  std::uint8_t flip_mask = 0;  ///< bits flipped on the way
};

/// Decides the fault for every byte sent on any link (`context` is the pointer given with the hook).
using fault_hook = byte_fault (*)(void* context, std::size_t link, std::uint64_t time, std::uint8_t byte);

/// Seconds taken by `byte_times` bytes at `bits_per_second`, with `bits_per_byte` line bits per byte
/// (10 for a UART frame of start bit, 8 data bits and stop bit).
constexpr double byte_times_to_seconds(std::uint64_t byte_times, double bits_per_second,
                                       unsigned bits_per_byte = 10) noexcept {
  return static_cast<double>(byte_times) * static_cast<double>(bits_per_byte) / bits_per_second;
}

/// The idle time after which a node's line counts as idle, by default (docs/protocol.md 1.10).
constexpr std::uint32_t default_idle_byte_times = 2;

/// A ring of up to `MaxNodes` nodes that the caller owns (see above).
template <std::size_t MaxNodes = 15>
class simulator {
  static_assert(MaxNodes >= 2 && MaxNodes <= 15, "a ring has 2 to 15 nodes");

 public:
  static constexpr std::size_t max_nodes = MaxNodes;  ///< the most nodes the ring takes

  /// `idle_byte_times`: how long a link carries no byte before its receiver's line counts as idle (at least
  /// 1); 0 never tells a node that its line is idle.
  explicit simulator(std::uint32_t idle_byte_times = default_idle_byte_times) noexcept
      : idle_byte_times_(idle_byte_times) {}

  /// Adds the next node round the ring; false when the ring is full.
  [[nodiscard]] bool add(byte_port& node) noexcept {
    if (count_ == MaxNodes) return false;
    nodes_[count_++] = &node;
    return true;
  }

  std::size_t size() const noexcept { return count_; }  ///< nodes added
  /// True when the ring has 2..MaxNodes nodes and can run.
  bool ready() const noexcept { return count_ >= 2; }
  std::uint64_t now() const noexcept { return now_; }  ///< byte-times run so far
  /// Bytes delivered since the start (a measure of simulation work: node-byte steps).
  std::uint64_t bytes_delivered() const noexcept { return delivered_; }
  /// The idle time of a line, in byte-times (the constructor's argument).
  std::uint32_t idle_byte_times() const noexcept { return idle_byte_times_; }

  // ---- faults ----
  /// The next byte sent on `link` never arrives.
  void drop_next(std::size_t link) noexcept {
    if (link < count_) faults_[link].drop_next = true;
  }
  /// The next byte sent on `link` arrives with the bits of `mask` flipped.
  void flip_next(std::size_t link, std::uint8_t mask) noexcept {
    if (link < count_) faults_[link].flip_mask = mask;
  }
  /// Cuts `link` (no byte arrives) or, with `cut` false, mends it.
  void cut(std::size_t link, bool cut = true) noexcept {
    if (link < count_) faults_[link].cut = cut;
  }
  /// Calls `hook` for every byte sent on any link (in addition to the faults above); nullptr removes it.
  void set_fault_hook(fault_hook hook, void* context = nullptr) noexcept {
    hook_ = hook;
    hook_context_ = context;
  }

  /// One byte-time. `trace(const link_byte&)` is called for every byte sent on any link, and
  /// `trace(const line_idle_event&)` for every idle line, if `trace` accepts that.
  template <class Trace>
  void step(Trace&& trace) {
    if (!ready()) return;
    bool sent[MaxNodes] = {};
    link_byte bytes[MaxNodes] = {};
    for (std::size_t i = 0; i < count_; ++i) {
      std::uint8_t byte = 0;
      if (!nodes_[i]->transmit(byte)) continue;
      fault& f = faults_[i];
      byte_fault injected;
      if (hook_ != nullptr) injected = hook_(hook_context_, i, now_, byte);
      const auto flip = static_cast<std::uint8_t>(f.flip_mask ^ injected.flip_mask);
      bytes[i] = {now_, i, byte, static_cast<std::uint8_t>(byte ^ flip), !(f.cut || f.drop_next || injected.drop)};
      f.flip_mask = 0;
      f.drop_next = false;
      sent[i] = true;
    }
    for (std::size_t i = 0; i < count_; ++i) {
      const std::size_t next = i + 1 == count_ ? 0 : i + 1;
      if (sent[i] && bytes[i].delivered) {
        nodes_[next]->receive(bytes[i].received);
        ++delivered_;
        quiet_[next] = 0;
      } else if (quiet_[next] != idle_byte_times_ && ++quiet_[next] == idle_byte_times_ &&
                 nodes_[next]->in_message()) {
        nodes_[next]->line_idle();
        if constexpr (std::is_invocable_v<Trace&, const line_idle_event&>) trace(line_idle_event{now_, i});
      }
      if (sent[i]) trace(bytes[i]);
    }
    ++now_;
  }
  /// One byte-time, without a trace.
  void step() {
    step([](const link_byte&) {});
  }

  /// Runs `byte_times` steps.
  template <class Trace>
  void run(std::uint64_t byte_times, Trace&& trace) {
    for (std::uint64_t t = 0; t < byte_times; ++t) step(trace);
  }
  /// Runs `byte_times` steps, without a trace.
  void run(std::uint64_t byte_times) {
    for (std::uint64_t t = 0; t < byte_times; ++t) step();
  }

  /// True when no node has anything to send.
  bool quiet() const noexcept {
    for (std::size_t i = 0; i < count_; ++i) {
      if (nodes_[i]->transmit_pending()) return false;
    }
    return true;
  }

 private:
  struct fault {
    bool cut = false;
    bool drop_next = false;
    std::uint8_t flip_mask = 0;
  };

  byte_port* nodes_[MaxNodes] = {};
  fault faults_[MaxNodes] = {};
  std::uint32_t quiet_[MaxNodes] = {};  // byte-times since node i's incoming link last delivered a byte
  fault_hook hook_ = nullptr;
  void* hook_context_ = nullptr;
  std::size_t count_ = 0;
  std::uint64_t now_ = 0;
  std::uint64_t delivered_ = 0;
  std::uint32_t idle_byte_times_;
};

}  // namespace trionet::ring
