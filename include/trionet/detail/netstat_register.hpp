// The register behind a ring node's NETSTAT (docs/protocol.md 1.6; the bits are ring/netstat.hpp), which the
// two sides of a node share without a lock.
//
// The link side raises bits 1..4 (a forwarded message lost, a CRC error, a frame error, a receive overflow);
// the program side raises bit 0 (an own message refused), reads NETSTAT and clears it. Each byte of the
// register is written by one side only: `raised_` by the link side, `cleared_` by the program side. A bit
// 1..4 is raised while `raised_` and `cleared_` differ in it, so the link side raises a bit by flipping it in
// `raised_` (if it is not raised already) and clearing copies `raised_` into `cleared_`. Bit 0 is never raised
// by the link side, so the program side keeps it in `cleared_` itself. Cost: 2 bytes.
#pragma once

#include <cstdint>

#include "trionet/detail/single_writer.hpp"

namespace trionet::detail {

/// NETSTAT: errors since it was last cleared, shared by the link side and the program side (see the file
/// comment). An error raised while NETSTAT is being cleared is either kept or cleared with it, never lost
/// otherwise.
class netstat_register {
 public:
  /// Link side: raises `bits` (bits 1..4; bit 0 is the program side's).
  void raise(std::uint8_t bits) noexcept {
    const std::uint8_t raised = raised_.load();
    const std::uint8_t pending = static_cast<std::uint8_t>(bits & ~(raised ^ cleared_.load()) & ~1u);
    if (pending != 0) raised_.store(static_cast<std::uint8_t>(raised ^ pending));
  }
  /// Program side: raises bit 0 (an own message refused).
  void raise_tx_timeout() noexcept { cleared_.store(static_cast<std::uint8_t>(cleared_.load() | 1u)); }
  /// Program side: the raised bits.
  std::uint8_t read() const noexcept { return static_cast<std::uint8_t>(raised_.load() ^ cleared_.load()); }
  /// Program side: clears every bit.
  void clear() noexcept { cleared_.store(raised_.load()); }

 private:
  single_writer<std::uint8_t> raised_;   // link side; bit 0 always 0
  single_writer<std::uint8_t> cleared_;  // program side; bit 0 is the TX timeout itself
};

}  // namespace trionet::detail
