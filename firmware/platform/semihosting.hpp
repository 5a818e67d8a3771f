// Arm semihosting: the target asks the debugger (here qemu, -semihosting-config enable=on,target=native) to
// print text and to exit with a status. A `bkpt 0xAB` with the operation in r0 and its argument in r1.
// Only the qemu test image uses this: on real hardware without a debugger the bkpt would fault.
#pragma once

#include <cstdint>

namespace semihosting {

enum operation : std::uint32_t {
  sys_write0 = 0x04,         ///< print a NUL-terminated string
  sys_exit = 0x18,           ///< angel_SWIReason_ReportException: stop, with a reason
  sys_exit_extended = 0x20,  ///< the same with a parameter block { reason, exit code }
};

/// ADP_Stopped_ApplicationExit: a normal end of program.
constexpr std::uint32_t application_exit = 0x20026;

inline std::uint32_t call(std::uint32_t op, const void* argument) noexcept {
  std::uint32_t result;
  __asm__ volatile(
      "mov r0, %[op]\n\t"
      "mov r1, %[arg]\n\t"
      "bkpt 0xAB\n\t"
      "mov %[result], r0"
      : [result] "=r"(result)
      : [op] "r"(op), [arg] "r"(argument)
      : "r0", "r1", "memory");
  return result;
}

inline void write(const char* text) noexcept { static_cast<void>(call(sys_write0, text)); }

/// Prints `value` in decimal.
inline void write_unsigned(std::uint32_t value) noexcept {
  char text[12];
  char* p = text + sizeof text;
  *--p = '\0';
  do {
    *--p = static_cast<char>('0' + value % 10);
    value /= 10;
  } while (value != 0);
  write(p);
}

/// Prints one line: `name` then `value` in decimal.
inline void report(const char* name, std::uint32_t value) noexcept {
  write(name);
  write_unsigned(value);
  write("\n");
}

/// Ends the emulation; qemu exits with `code`. SYS_EXIT_EXTENDED carries the code on 32-bit Arm; should a
/// host not know it, plain SYS_EXIT still tells success (ApplicationExit) from failure (any other reason).
[[noreturn]] inline void exit(std::uint32_t code) noexcept {
  const std::uint32_t block[2] = {application_exit, code};
  static_cast<void>(call(sys_exit_extended, block));
  static_cast<void>(call(sys_exit, reinterpret_cast<const void*>(code == 0 ? application_exit : 0x20023u)));
  for (;;) {
  }
}

}  // namespace semihosting
