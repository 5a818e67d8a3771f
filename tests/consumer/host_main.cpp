// An outside program that links the installed host library (trionet::host): reads a candump line, writes
// the frame to a pcapng capture in memory and reads it back.
#include <trionet/host/candump.hpp>
#include <trionet/host/capture.hpp>
#include <trionet/host/pcapng.hpp>

#include <cstdio>
#include <sstream>

int main() {
  using namespace trionet::host;
  const candump_result line = parse_candump_line("(1700000000.123456) can0 028#0100000000020D7A R");
  if (!line || !line.record.classic_frame() || line.record.direction != 'R') {
    std::puts("host_consumer: candump line not read");
    return 1;
  }
  std::stringstream capture;
  pcapng_writer writer(capture);
  const pcapng_interface_result bus = writer.add_interface("can0", capture_network::can);
  const auto record = socketcan_record(line.record.frame);
  if (!bus || writer.write(bus.id, 1700000000123456000ull, trionet::byte_view(record.data(), record.size())) !=
                  pcapng_write_status::ok) {
    std::puts("host_consumer: capture not written");
    return 1;
  }
  pcapng_reader reader(capture);
  const pcapng_read_result read = reader.next();
  const socketcan_record_result frame = read_socketcan_record(read.record.bytes);
  if (!read || !frame || format_candump_frame(frame.frame) != "028#0100000000020D7A") {
    std::puts("host_consumer: capture not read back");
    return 1;
  }
  std::puts("host_consumer: ok");
  return 0;
}
