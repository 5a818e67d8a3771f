// A seeded source of 32-bit random numbers as `unsigned` (std::mt19937's result_type is wider than unsigned on
// LP64, and the tests narrow it explicitly once, here).
#pragma once

#include <random>

namespace trionet::test {

struct rng {
  std::mt19937 engine;
  explicit rng(unsigned seed) : engine(seed) {}
  unsigned operator()() { return static_cast<unsigned>(engine()); }
};

}  // namespace trionet::test
