// What a BASIC program reaches outside itself: its controller. The interpreter (task.hpp) calls nothing else,
// so a program runs the same on a simulated ring node (src/sim/ring_network.cpp), on a test double, or on
// anything else that implements this interface.
//
//   PRINT #n,...        print(n, text)              n = 0: the terminal; 1, 2: serial ports; 5..7: Motion
//                                                   Perfect's channels; 10..24: the network
//   SEND(n,1,vr,value)  send_variable(n, vr, value)
//   SEND(n,2,offset)    send_keypad_offset(n, offset)
//   KEY#n, GET #n,x     key(n), get(n)              n = 3 (through DEFKEY) or 4 (raw)
//   NETSTAT, NETSTAT=0  netstat(), clear_netstat()
//   VR(i), VR(i)=x      vr(i), set_vr(i, x)         i < vr_count()
//   axes, IN, OP, TABLE, WDOG, TICKS' clock        hardware(): the controller's machine (machine.hpp)
//
// A call never blocks: `busy` (or a PRINT that queued only part of its text) makes the statement wait and try
// again at the next byte-time, while the ring goes on.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "basic/machine.hpp"

namespace trionet::basic {

/// Outcome of a controller call.
enum class io_status : std::uint8_t {
  ok,
  busy,                    ///< not now: no room to send yet, or nothing received yet; try again later
  bad_channel,             ///< not a channel this statement can use
  bad_address,             ///< not a BASIC address 10..24
  bad_type,                ///< SEND type other than 1 (variable) or 2 (keypad offset)
  character_out_of_range,  ///< a character the channel cannot carry (the ring carries 0..127)
  vr_out_of_range,         ///< SEND's VR number outside 0..16383
  value_out_of_range,      ///< SEND's value outside what the network carries
  offset_out_of_range,     ///< SEND's keypad offset not a BASIC address 10..24
};

constexpr const char* to_string(io_status status) noexcept {
  switch (status) {
    case io_status::ok:
      return "ok";
    case io_status::busy:
      return "busy";
    case io_status::bad_channel:
      return "bad_channel";
    case io_status::bad_address:
      return "bad_address";
    case io_status::bad_type:
      return "bad_type";
    case io_status::character_out_of_range:
      return "character_out_of_range";
    case io_status::vr_out_of_range:
      return "vr_out_of_range";
    case io_status::value_out_of_range:
      return "value_out_of_range";
    case io_status::offset_out_of_range:
      return "offset_out_of_range";
  }
  return "unknown";
}

/// PRINT #n: how many characters of the text were queued (ok with fewer than all: the rest waits for room).
struct [[nodiscard]] print_result {
  io_status status;
  std::size_t queued;
  constexpr explicit operator bool() const noexcept { return status == io_status::ok; }
};

/// KEY#n: whether a character is waiting.
struct [[nodiscard]] key_result {
  io_status status;
  bool waiting;
  constexpr explicit operator bool() const noexcept { return status == io_status::ok; }
};

/// GET #n: the character (already translated through DEFKEY on channel 3), or `busy` when none is waiting.
struct [[nodiscard]] get_result {
  io_status status;
  std::uint8_t value;
  constexpr explicit operator bool() const noexcept { return status == io_status::ok; }
};

class controller {
 public:
  /// Queues as much of `text` as fits now, in whole messages; never blocks.
  virtual print_result print(int channel, std::string_view text) = 0;
  /// `busy` when there is no room to queue the message yet (nothing is queued and NETSTAT is not touched).
  virtual io_status send_variable(int address, int vr, double value) = 0;
  virtual io_status send_keypad_offset(int address, int offset) = 0;
  virtual key_result key(int channel) = 0;
  virtual get_result get(int channel) = 0;

  virtual std::uint32_t netstat() = 0;
  virtual void clear_netstat() = 0;

  virtual std::size_t vr_count() const = 0;
  virtual double vr(std::size_t index) const = 0;
  virtual void set_vr(std::size_t index, double value) = 0;

  /// The axes, digital I/O, TABLE, watchdog and servo clock of this controller.
  virtual machine& hardware() = 0;

 protected:
  controller() = default;
  controller(const controller&) = default;
  controller& operator=(const controller&) = default;
  ~controller() = default;
};

}  // namespace trionet::basic
