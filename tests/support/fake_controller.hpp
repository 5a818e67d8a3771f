// A controller for interpreter tests (basic/controller.hpp): records what a program sends, serves characters
// the test queues, and can refuse room to make PRINT # and SEND wait.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "basic/controller.hpp"
#include "basic/machine.hpp"
#include "basic/program.hpp"

namespace trionet::test {

class fake_controller final : public basic::controller {
 public:
  std::map<int, std::string> printed;          ///< everything PRINTed, per channel
  std::size_t room = 1000000;                  ///< characters PRINT # may queue now (each call uses it up)
  bool send_room = true;                       ///< false: SEND gets `busy`
  std::deque<std::uint8_t> received;           ///< characters for GET # / KEY# (channels 3 and 4)
  std::vector<std::tuple<int, int, double>> variables_sent;  ///< SEND(n,1,vr,value)
  std::vector<std::pair<int, int>> offsets_sent;             ///< SEND(n,2,offset)
  std::uint32_t netstat_value = 0;
  std::vector<double> vrs = std::vector<double>(1024, 0.0);
  basic::machine hardware_state;  ///< axes, I/O, TABLE, servo clock: the test calls servo_tick() itself

  basic::print_result print(int channel, std::string_view text) override {
    const bool terminal = channel == 0 || channel == 1 || channel == 2 || (channel >= 5 && channel <= 7);
    if (!terminal && (channel < 10 || channel > 24)) return {basic::io_status::bad_channel, 0};
    for (char c : text) {
      if (!terminal && static_cast<unsigned char>(c) > 127) return {basic::io_status::character_out_of_range, 0};
    }
    const std::size_t n = text.size() < room ? text.size() : room;
    room -= n;
    printed[channel] += std::string(text.substr(0, n));
    return {basic::io_status::ok, n};
  }
  basic::io_status send_variable(int address, int vr, double value) override {
    if (address < 10 || address > 24) return basic::io_status::bad_address;
    if (vr < 0 || vr > 16383) return basic::io_status::vr_out_of_range;
    if (!send_room) return basic::io_status::busy;
    variables_sent.emplace_back(address, vr, value);
    return basic::io_status::ok;
  }
  basic::io_status send_keypad_offset(int address, int offset) override {
    if (address < 10 || address > 24) return basic::io_status::bad_address;
    if (offset < 10 || offset > 24) return basic::io_status::offset_out_of_range;
    if (!send_room) return basic::io_status::busy;
    offsets_sent.emplace_back(address, offset);
    return basic::io_status::ok;
  }
  basic::key_result key(int channel) override {
    if (channel != 3 && channel != 4) return {basic::io_status::bad_channel, false};
    return {basic::io_status::ok, !received.empty()};
  }
  basic::get_result get(int channel) override {
    if (channel != 3 && channel != 4) return {basic::io_status::bad_channel, 0};
    if (received.empty()) return {basic::io_status::busy, 0};
    const std::uint8_t c = received.front();
    received.pop_front();
    return {basic::io_status::ok, c};
  }
  std::uint32_t netstat() override { return netstat_value; }
  void clear_netstat() override { netstat_value = 0; }
  std::size_t vr_count() const override { return vrs.size(); }
  double vr(std::size_t index) const override { return vrs[index]; }
  void set_vr(std::size_t index, double value) override { vrs[index] = value; }
  basic::machine& hardware() override { return hardware_state; }
};

}  // namespace trionet::test
