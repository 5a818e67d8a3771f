// Linux SocketCAN port: see can_socketcan.hpp.
#include "trionet/host/socketcan.hpp"

#include <fcntl.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace trionet::host {

::can_frame to_socketcan(const can::frame& frame) noexcept {
  ::can_frame out{};
  out.can_id = frame.id;
  out.len = frame.dlc > CAN_MAX_DLEN ? static_cast<std::uint8_t>(CAN_MAX_DLEN) : frame.dlc;
  std::memcpy(out.data, frame.data, sizeof out.data);
  return out;
}

can::frame from_socketcan(const ::can_frame& frame) noexcept {
  can::frame out;
  out.id = frame.can_id & ~static_cast<std::uint32_t>(CAN_ERR_FLAG);
  out.dlc = frame.len > CAN_MAX_DLEN ? static_cast<std::uint8_t>(CAN_MAX_DLEN) : frame.len;
  std::memcpy(out.data, frame.data, sizeof out.data);
  return out;
}

socketcan_port::~socketcan_port() {
  close();
}

socketcan_open_result socketcan_port::open(const std::string& interface_name) {
  close();
  if (interface_name.empty() || interface_name.size() >= IFNAMSIZ)
    return {socketcan_status::name_too_long, 0};
  const int handle = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (handle < 0) return {socketcan_status::socket, errno};
  const unsigned index = ::if_nametoindex(interface_name.c_str());
  if (index == 0) {
    const int error = errno;
    ::close(handle);
    return {socketcan_status::no_such_interface, error};
  }
  ::sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  // sockaddr_can is the address type bind() expects for PF_CAN; the cast is the socket API's contract.
  if (::bind(handle, reinterpret_cast<const ::sockaddr*>(&address), sizeof address) != 0) {
    const int error = errno;
    ::close(handle);
    return {socketcan_status::bind, error};
  }
  socket_ = handle;
  return {};
}

void socketcan_port::close() noexcept {
  if (socket_ >= 0) ::close(socket_);
  socket_ = -1;
}

can::transmit_status socketcan_port::send(const can::frame& outgoing) noexcept {
  if (socket_ < 0) return can::transmit_status::failed;
  const ::can_frame raw = to_socketcan(outgoing);
  const ssize_t written = ::write(socket_, &raw, sizeof raw);
  if (written == static_cast<ssize_t>(sizeof raw)) return can::transmit_status::ok;
  if (written < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) {
    return can::transmit_status::busy;
  }
  return can::transmit_status::failed;
}

socketcan_receive_status socketcan_port::receive(can::frame& out, int timeout_ms) noexcept {
  if (socket_ < 0) return socketcan_receive_status::failed;
  ::pollfd waiting{socket_, POLLIN, 0};
  const int ready = ::poll(&waiting, 1, timeout_ms);
  if (ready == 0) return socketcan_receive_status::timeout;
  if (ready < 0) return socketcan_receive_status::failed;
  ::can_frame raw{};
  const ssize_t got = ::read(socket_, &raw, sizeof raw);
  if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return socketcan_receive_status::timeout;
  if (got != static_cast<ssize_t>(sizeof raw)) return socketcan_receive_status::failed;
  out = from_socketcan(raw);
  return (raw.can_id & CAN_ERR_FLAG) != 0 ? socketcan_receive_status::error_frame
                                          : socketcan_receive_status::ok;
}

const char* to_string(socketcan_status status) {
  switch (status) {
    case socketcan_status::ok:
      return "ok";
    case socketcan_status::name_too_long:
      return "name_too_long";
    case socketcan_status::socket:
      return "socket";
    case socketcan_status::no_such_interface:
      return "no_such_interface";
    case socketcan_status::bind:
      return "bind";
  }
  return "unknown";
}

const char* to_string(socketcan_receive_status status) {
  switch (status) {
    case socketcan_receive_status::ok:
      return "ok";
    case socketcan_receive_status::error_frame:
      return "error_frame";
    case socketcan_receive_status::timeout:
      return "timeout";
    case socketcan_receive_status::failed:
      return "failed";
  }
  return "unknown";
}

}  // namespace trionet::host
