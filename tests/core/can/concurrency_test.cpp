// The two sides of a CAN VR-exchange node in two threads, no lock, no masking (docs/design.md, "Contexts"): a
// short run of the stress in tests/support/concurrency_stress.hpp. scripts/concurrency-test runs it long,
// under ThreadSanitizer.
#include <gtest/gtest.h>

#include "support/concurrency_stress.hpp"

TEST(CanConcurrency, ReceiveInterruptAndProgramThread) {
  trionet::stress::config cfg;
  cfg.link_steps = 100000;
  const trionet::stress::report r = trionet::stress::run_can(cfg);
  for (const std::string& f : r.failures) ADD_FAILURE() << f;
  EXPECT_GT(r.program_calls, 100u);
}
