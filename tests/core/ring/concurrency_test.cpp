// The two sides of a ring node in two threads, no lock, no masking (docs/design.md, "Contexts"): a short run
// of the stress in tests/support/concurrency_stress.hpp. scripts/concurrency-test runs it long, under
// ThreadSanitizer.
#include <gtest/gtest.h>

#include "support/concurrency_stress.hpp"

namespace {

// How much each thread did depends on the scheduler; the link side's steps and the program side's first
// tenth of them are certain (the link side waits for them before it ends).
void expect_passed(const trionet::stress::report& r) {
  for (const std::string& f : r.failures) ADD_FAILURE() << f;
  EXPECT_GT(r.frames_out, 100u);
  EXPECT_GE(r.program_calls, 10000u);
}

}  // namespace

TEST(RingConcurrency, MotionCoordinatorLinkInterruptAndProgramThread) {
  trionet::stress::config cfg;
  cfg.link_steps = 100000;
  const trionet::stress::report r = trionet::stress::run_motion_coordinator(cfg);
  expect_passed(r);
}

TEST(RingConcurrency, KeypadLinkInterruptAndKeyScan) {
  trionet::stress::config cfg;
  cfg.link_steps = 100000;
  cfg.seed = 2;
  const trionet::stress::report r = trionet::stress::run_keypad(cfg);
  expect_passed(r);
}

// The link side in bulk, as a DMA-fed UART: runs of bytes received at once, transmitted at once or a byte at
// a time.
TEST(RingConcurrency, MotionCoordinatorDmaLinkAndProgramThread) {
  trionet::stress::config cfg;
  cfg.link_steps = 100000;
  cfg.dma = true;
  expect_passed(trionet::stress::run_motion_coordinator(cfg));
}

TEST(RingConcurrency, KeypadDmaLinkAndKeyScan) {
  trionet::stress::config cfg;
  cfg.link_steps = 100000;
  cfg.seed = 2;
  cfg.dma = true;
  expect_passed(trionet::stress::run_keypad(cfg));
}
