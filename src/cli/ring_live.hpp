// Pieces of the live ring commands (ring_live_cli.cpp, ring_join_cli.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "live.hpp"
#include "profile_cli.hpp"
#include "trionet/host/capture.hpp"
#include "trionet/host/link_device.hpp"
#include "trionet/ring/decoder.hpp"

namespace trionet::cli {

/// `trionet ring monitor|send|join ...`, entries of the ring part's command table; their help text.
int ring_monitor_main(const words& args);
int ring_send_main(const words& args);
int ring_join_main(const words& args);
extern const char* const ring_live_usage;
const option_list& ring_monitor_options();
const option_list& ring_send_options();
const option_list& ring_join_options();

/// One direction of a ring link as this host sees it: every byte is decoded (a receiver's view of every
/// message, whatever its hops), cut into capture records, and counted.
class ring_tap {
 public:
  /// Gets each decoder result and the time of the byte that completed it.
  using sink = std::function<void(const ring::decode_result&, std::uint64_t time_ns)>;

  /// `capture` may be null; `link_name` names the capture interface ("received on /dev/ttyUSB0").
  ring_tap(live::capture_file* capture, const std::string& link_name);

  /// Bytes that crossed the link at `time_ns`; each completed message or error goes to `out`.
  void push(byte_view bytes, std::uint64_t time_ns, const sink& out);
  void push(std::uint8_t byte, std::uint64_t time_ns, const sink& out);
  /// The idle line (or the end): a message open is cut short (`idle_line`); the capture record ends.
  void idle(std::uint64_t time_ns, const sink& out);
  /// True while a message or a capture record is open.
  [[nodiscard]] bool open() const noexcept { return decoder_.open() || records_.open(); }

  /// The hops of the message the last result was about (0 for stray bytes): a node's own traffic is hops 1.
  [[nodiscard]] std::uint8_t last_hops() const noexcept { return last_hops_; }

  /// NETSTAT-style counters as one event appended to `out`: bytes, messages by type, CRC and frame errors
  /// (in all, then by reason where not 0: `idle_line` counts the messages the idle line cut), and the NETSTAT
  /// bits a receiver of everything would show (4 CRC, 8 frame).
  void counters(std::string& out, std::uint64_t time_ns) const;
  /// The counters' fields added to `e` with `prefix` ("in_" ...).
  void add_counters(event& e, const std::string& prefix) const;

  [[nodiscard]] std::uint64_t messages() const noexcept { return messages_; }

 private:
  void report(const ring::decode_result& r, std::uint64_t time_ns, const sink& out);

  profile_decoder decoder_;
  host::ring_record_splitter records_;
  live::capture_file* capture_;
  std::uint32_t interface_ = 0;
  std::uint8_t open_hops_ = 0;  // the header of the message open in the decoder
  std::uint8_t last_hops_ = 0;
  std::uint64_t bytes_ = 0;
  std::uint64_t messages_ = 0;
  std::uint64_t by_type_[5] = {};
  std::uint64_t crc_errors_ = 0;
  std::uint64_t no_room_ = 0;
  std::map<std::string, std::uint64_t> frame_errors_;
};

/// What `ring join` was asked for.
struct join_settings {
  std::string port;
  host::link_options link;
  int idle_ms = 50;
  bool json = false;
  bool trace = false;
  std::string pcap;
  int learn_keypad = 0;      ///< --learn-keypad N: the keypad's BASIC address (0: no learning)
  int keypad_offset = 0;     ///< --keypad-offset M: the keypad's way back to this MC (BASIC address)
  std::string learn_output;  ///< -o PROFILE
};

int join_mc(const join_settings& settings);
int join_keypad(const join_settings& settings);

}  // namespace trionet::cli
