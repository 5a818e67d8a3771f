// Linux SocketCAN port: a `trionet::can::port` on a raw CAN socket (can0, vcan0, ...), plus conversion
// between `trionet::can::frame` and the kernel's `struct can_frame`.
//
// The frame identifier word uses the same flag bits as the kernel (CAN_EFF_FLAG, CAN_RTR_FLAG), so conversion
// copies it; error frames (CAN_ERR_FLAG) are not CAN frames to the exchange and convert with that bit cleared
// but are reported by `receive` as `error_frame`. Host code only (system calls); not for firmware.
#pragma once

#include <linux/can.h>

#include <cstdint>
#include <string>

#include <trionet/can/frame.hpp>
#include <trionet/can/port.hpp>

namespace trionet::host {

/// The kernel frame for `frame`: identifier word and DLC copied (DLC above 8 becomes 8), data copied.
[[nodiscard]] ::can_frame to_socketcan(const can::frame& frame) noexcept;

/// The library frame for a kernel frame: identifier word without CAN_ERR_FLAG, DLC (len) capped at 8, data.
[[nodiscard]] can::frame from_socketcan(const ::can_frame& frame) noexcept;

/// Whether opening a SocketCAN interface succeeded (on failure `system_error` holds errno).
enum class socketcan_status : std::uint8_t {
  ok,
  name_too_long,      ///< the interface name does not fit IFNAMSIZ
  socket,             ///< socket(PF_CAN) failed: no CAN support in this kernel (EAFNOSUPPORT), no permission
  no_such_interface,  ///< if_nametoindex failed
  bind,               ///< bind() failed
};

/// An open result: status and errno.
struct [[nodiscard]] socketcan_open_result {
  socketcan_status status = socketcan_status::ok;
  int system_error = 0;
  explicit operator bool() const noexcept { return status == socketcan_status::ok; }
};

/// What `receive` got.
enum class socketcan_receive_status : std::uint8_t {
  ok,           ///< a CAN frame was read into `out`
  error_frame,  ///< the kernel delivered an error frame (CAN_ERR_FLAG); `out` holds it without the flag
  timeout,      ///< nothing arrived in time
  failed,       ///< poll or read failed, or the socket is closed
};

/// A raw CAN socket bound to one interface. send() is non-blocking: a full kernel queue is `busy`.
/// Not copyable; closes the socket on destruction. Not for an ISR (system calls).
class socketcan_port final : public can::port {
 public:
  socketcan_port() = default;
  ~socketcan_port();
  socketcan_port(const socketcan_port&) = delete;
  socketcan_port& operator=(const socketcan_port&) = delete;

  /// Opens a raw CAN socket on `interface_name` (closing any socket already open).
  [[nodiscard]] socketcan_open_result open(const std::string& interface_name);
  void close() noexcept;
  [[nodiscard]] bool is_open() const noexcept { return socket_ >= 0; }
  /// The socket's descriptor (-1 when closed), to wait for it in poll() together with other descriptors.
  [[nodiscard]] int fd() const noexcept { return socket_; }

  [[nodiscard]] can::transmit_status send(const can::frame& outgoing) noexcept override;

  /// Waits up to `timeout_ms` milliseconds (0 = poll, negative = forever) for one frame.
  [[nodiscard]] socketcan_receive_status receive(can::frame& out, int timeout_ms) noexcept;

 private:
  int socket_ = -1;
};

/// The enumerator's name ("no_such_interface"), for messages.
[[nodiscard]] const char* to_string(socketcan_status status);
[[nodiscard]] const char* to_string(socketcan_receive_status status);

}  // namespace trionet::host
