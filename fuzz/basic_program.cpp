// Fuzz harness: the BASIC compiler and interpreter (src/basic/) on arbitrary program text.
//
// The whole input is the program text. Choices for the controller (how much room PRINT # and SEND find, which
// characters GET # receives, NETSTAT, inputs) and the run (statements per turn, servo ticks) come from a
// generator seeded with the input's hash. The invariants are those of basic_checks.hpp.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "basic_checks.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  trionet_fuzz::compile_and_run(std::string_view(reinterpret_cast<const char*>(data), size),
                                trionet_fuzz::hash(data, size));
  return 0;
}
