// The two sides of a Genius device in two threads, no lock, no masking (docs/design.md, "Contexts"): a short
// run of the stress in tests/support/concurrency_stress_genius.hpp. scripts/concurrency-test runs it long,
// under ThreadSanitizer.
#include <gtest/gtest.h>

#include "support/concurrency_stress_genius.hpp"

TEST(GeniusConcurrency, UartAndTimerInterruptsAndProgramThread) {
  trionet::stress::config cfg;
  cfg.link_steps = 100000;
  cfg.seed = 3;
  const trionet::stress::report r = trionet::stress::run_genius_device(cfg);
  for (const std::string& f : r.failures) ADD_FAILURE() << f;
  // Each thread's share depends on the scheduler; the link side's characters and the program side's first
  // calls are certain (the link side waits for them before it ends).
  EXPECT_GE(r.link_steps, 100000u);
  EXPECT_GT(r.frames_out, 100u);
  EXPECT_GT(r.own_frames, 10u);
  EXPECT_GE(r.program_calls, 2500u);
}
