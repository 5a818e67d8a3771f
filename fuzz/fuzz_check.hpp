// What every harness in fuzz/ shares: an invariant check that aborts (so libFuzzer and the corpus replay both
// stop on it with the input that broke it), and a reader that turns the fuzz input into choices.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

/// Checks an invariant; on failure prints it and aborts. Active in every build type (not an assert).
#define FUZZ_CHECK(condition)                                                                          \
  do {                                                                                                  \
    if (!(condition)) ::trionet_fuzz::fail(#condition, __FILE__, __LINE__);                            \
  } while (false)

namespace trionet_fuzz {

[[noreturn]] inline void fail(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: invariant failed: %s\n", file, line, condition);
  std::fflush(stderr);
  std::abort();
}

/// True when `text` has no byte below 0x20 and no DEL: a line a terminal shows as it is (what a message of
/// the tool must be, whatever the input).
template <class Text>
bool printable_line(const Text& text) noexcept {
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) return false;
  }
  return true;
}

/// Reads the fuzz input front to back as choices; past the end every read gives 0 and `done()` is true.
class input_reader {
 public:
  input_reader(const std::uint8_t* data, std::size_t size) noexcept : data_(data), size_(size) {}

  bool done() const noexcept { return at_ >= size_; }
  std::size_t remaining() const noexcept { return done() ? 0 : size_ - at_; }
  const std::uint8_t* here() const noexcept { return data_ + at_; }

  std::uint8_t byte() noexcept { return done() ? std::uint8_t{0} : data_[at_++]; }
  std::uint16_t u16() noexcept {
    const auto high = byte();
    return static_cast<std::uint16_t>(high << 8 | byte());
  }
  std::uint32_t u32() noexcept {
    const std::uint32_t high = u16();
    return high << 16 | u16();
  }
  /// Skips `n` bytes (at most what is left) and returns how many were skipped.
  std::size_t skip(std::size_t n) noexcept {
    const std::size_t taken = n < remaining() ? n : remaining();
    at_ += taken;
    return taken;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t at_ = 0;
};

/// A small deterministic generator (xorshift32) for choices derived from the input, e.g. split points.
class split_source {
 public:
  explicit split_source(std::uint32_t seed) noexcept : state_(seed == 0 ? 0x9E3779B9U : seed) {}
  std::uint32_t next() noexcept {
    state_ ^= state_ << 13;
    state_ ^= state_ >> 17;
    state_ ^= state_ << 5;
    return state_;
  }

 private:
  std::uint32_t state_;
};

/// FNV-1a over the input: a seed that changes whenever the input does.
inline std::uint32_t hash(const std::uint8_t* data, std::size_t size) noexcept {
  std::uint32_t h = 2166136261U;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 16777619U;
  return h;
}

}  // namespace trionet_fuzz
