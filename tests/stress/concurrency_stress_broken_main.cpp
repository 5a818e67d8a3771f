// trionet_concurrency_stress_broken: the same stress with the concurrency contract deliberately broken, to
// show that the test can fail. Here `single_writer` (include/trionet/detail/single_writer.hpp) of every size the
// nodes use is a plain variable: the same loads and stores by the same sides, without the atomic. The
// nodes' queue indices, NETSTAT bytes, keypad offset and mode and all counters become data races, and
// ThreadSanitizer must report one. scripts/concurrency-test requires it for each node; never run it as a
// test that should pass.
//
//   trionet_concurrency_stress_broken [--steps N] [--seed S] [--node all|NODE[,NODE...]] [--link uart|dma]
#include <cstdint>

#include "trionet/detail/single_writer.hpp"

namespace trionet {

namespace broken {
/// `single_writer`'s interface over a plain variable (no atomic, no ordering).
template <class T>
class plain_single_writer {
 public:
  constexpr plain_single_writer() noexcept = default;
  constexpr explicit plain_single_writer(T value) noexcept : value_(value) {}
  T load() const noexcept { return value_; }
  T acquire() const noexcept { return value_; }
  void store(T value) noexcept { value_ = value; }
  void release(T value) noexcept { value_ = value; }
  void add(T n) noexcept { value_ = static_cast<T>(value_ + n); }
  void increment() noexcept { add(T{1}); }

 private:
  T value_{};
};
}  // namespace broken

// Declared before any node is, so that the nodes below are built on them.
namespace detail {
template <>
class single_writer<std::uint8_t> : public broken::plain_single_writer<std::uint8_t> {
 public:
  using plain_single_writer::plain_single_writer;
};
template <>
class single_writer<std::uint16_t> : public broken::plain_single_writer<std::uint16_t> {
 public:
  using plain_single_writer::plain_single_writer;
};
template <>
class single_writer<std::uint32_t> : public broken::plain_single_writer<std::uint32_t> {
 public:
  using plain_single_writer::plain_single_writer;
};
}  // namespace detail

}  // namespace trionet

#include "stress/command_line.hpp"

int main(int argc, char** argv) {
  return trionet::stress::command_line("trionet_concurrency_stress_broken", argc, argv);
}
