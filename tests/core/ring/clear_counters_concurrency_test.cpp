// `clear_counters` while the link side runs in another thread (docs/design.md, "Contexts"): the program side
// asks, the link side clears its counters before it next counts. Between clears no count goes back; after the
// last clear the count is what came after it, to within the one header the link side was taking meanwhile.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

#include "support/ring_frames.hpp"
#include "trionet/ring.hpp"
#include "trionet/vr.hpp"

namespace ring = trionet::ring;

TEST(RingClearCountersConcurrency, ALinkThreadCountsFromTheClearsOfAProgramThread) {
  trionet::vr_table<8> vr;
  ring::motion_coordinator<> mc(vr);
  constexpr std::uint32_t messages = 20000;  // below 2^16: the traffic counters do not wrap
  const std::vector<std::uint8_t> message = trionet::test::chars(3, "ab");  // passes through: A = 3
  std::atomic<std::uint32_t> headers_fed{0};  // the test's own bookkeeping, not the node's
  std::atomic<bool> started{false};

  std::thread link([&] {  // the link side: a UART interrupt, a byte in and a byte out
    while (!started.load(std::memory_order_acquire)) std::this_thread::yield();
    std::uint8_t out = 0;
    for (std::uint32_t m = 0; m < messages; ++m) {
      for (std::size_t i = 0; i < message.size(); ++i) {
        (void)mc.receive(message[i]);
        if (i == 0) headers_fed.fetch_add(1, std::memory_order_release);
        while (mc.transmit(out)) {
        }
      }
    }
  });

  std::mt19937 rng(7);
  std::uint32_t before_clear = 0, after_clear = 0;  // headers fed around the last clear
  std::uint32_t seen = 0, clears = 0;
  started.store(true, std::memory_order_release);
  for (;;) {
    const std::uint32_t fed = headers_fed.load(std::memory_order_acquire);
    if (fed == messages) break;
    if (fed < messages / 2 && rng() % 64 == 0) {
      before_clear = headers_fed.load(std::memory_order_acquire);
      mc.clear_counters();
      after_clear = headers_fed.load(std::memory_order_acquire);
      seen = 0;
      ++clears;
      continue;
    }
    const std::uint32_t now = mc.forwarding_counters().messages_forwarded;
    ASSERT_GE(now, seen) << "a count went back between clears";
    // Counted since the last clear: at most what was fed since it was asked, and the header being taken.
    ASSERT_LE(now, headers_fed.load(std::memory_order_acquire) + 1 - before_clear);
    seen = now;
  }
  link.join();
  EXPECT_GT(clears, 0u);
  const ring::link_counters links = mc.forwarding_counters();
  EXPECT_LE(links.messages_forwarded, messages - before_clear);
  // (Signed: the link thread may have fed every message by the time the last clear returned, after_clear ==
  // messages; unsigned, the bound wrapped to 2^32 - 1 and the test failed on a busy machine.)
  EXPECT_GE(std::int64_t{links.messages_forwarded}, std::int64_t{messages} - after_clear - 1);
  EXPECT_EQ(links.forwards_failed(), 0u);
  EXPECT_EQ(links.messages_sent, 0u);
  EXPECT_EQ(mc.counters().frame_errors, 0u);
}
