// A virtual CAN interface for a test: used if it exists, created if it does not (which needs root, iproute2
// and the vcan kernel module) and then removed when the test ends. When it cannot be had, `missing()` says
// what stands in the way, found out rather than guessed, for the test's skip message.
#pragma once

#include <linux/can.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <string>

namespace trionet::test {

class vcan_interface {
 public:
  explicit vcan_interface(std::string name) : name_(std::move(name)) {
    if (::if_nametoindex(name_.c_str()) != 0) return;
    const std::string add = "ip link add dev " + name_ + " type vcan >/dev/null 2>&1 && ip link set up " +
                            name_ + " >/dev/null 2>&1";
    if (std::system(add.c_str()) != 0) {
      missing_ = why_missing();
      return;
    }
    created_ = true;
  }
  ~vcan_interface() {
    if (created_) (void)std::system(("ip link del " + name_ + " >/dev/null 2>&1").c_str());
  }
  vcan_interface(const vcan_interface&) = delete;
  vcan_interface& operator=(const vcan_interface&) = delete;

  const std::string& name() const { return name_; }
  bool usable() const { return missing_.empty(); }
  // Why the interface cannot be had (empty when it can).
  const std::string& missing() const { return missing_; }

 private:
  static std::string why_missing() {
    if (::geteuid() != 0) {
      return "creating a network interface needs root, and this test runs as uid " + std::to_string(::geteuid());
    }
    if (std::system("command -v ip >/dev/null 2>&1") != 0) return "the `ip` command (iproute2) is not installed";
    const int can_socket = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
    if (can_socket < 0) {
      return std::string("the kernel has no CAN socket support (socket(PF_CAN) failed: ") + std::strerror(errno) +
             ")";
    }
    ::close(can_socket);
    return "the kernel has CAN sockets but `ip link add type vcan` failed: the vcan module is missing or cannot "
           "be loaded here (modprobe vcan)";
  }

  std::string name_;
  std::string missing_;
  bool created_ = false;
};

}  // namespace trionet::test
