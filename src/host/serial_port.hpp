// Serial ports inside the host library (not installed): the step of open_serial (posix_link.hpp) that
// configures a descriptor already open, so that link_device can take the port's lock before it changes a
// setting.
#pragma once

#include <string>

#include "trionet/host/posix_link.hpp"

namespace trionet::host {

/// Configures the open serial port (or pty) `fd` as open_serial does: raw 8-bit, `baud`, `flow`, the old
/// settings kept in `saved` when given. False with `error` naming `path` and the cause (`fd` stays open).
bool configure_serial(int fd, const std::string& path, unsigned baud, std::string& error, flow_control flow,
                      serial_settings* saved);

}  // namespace trionet::host
