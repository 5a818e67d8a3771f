// Pieces the live-network commands share: see live.hpp.
#include "live.hpp"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "cli.hpp"
#include "trionet/can.hpp"
#include "trionet/host/candump.hpp"

namespace trionet::cli::live {

std::uint64_t now_ns() {
  timespec t{};
  ::clock_gettime(CLOCK_REALTIME, &t);
  return static_cast<std::uint64_t>(t.tv_sec) * 1000000000u + static_cast<std::uint64_t>(t.tv_nsec);
}

event& event::text(const std::string& field, std::string_view value) {
  fields.emplace_back(field, json_string(value));
  return *this;
}
event& event::number(const std::string& field, long long value) {
  fields.emplace_back(field, std::to_string(value));
  return *this;
}
event& event::number(const std::string& field, unsigned long long value) {
  fields.emplace_back(field, std::to_string(value));
  return *this;
}
event& event::real(const std::string& field, double value) {
  fields.emplace_back(field, format_real(value));
  return *this;
}
event& event::flag(const std::string& field, bool value) {
  fields.emplace_back(field, value ? "true" : "false");
  return *this;
}

event ring_event(std::uint64_t time_ns, const ring::decode_result& result) {
  const ring::message& m = result.msg;
  switch (result.status) {
    case ring::decode_status::incomplete:
    case ring::decode_status::frame_error:
      return event(time_ns, "frame_error").text("reason", ring::to_string(result.error));
    case ring::decode_status::no_room:
      return event(time_ns, "no_room").number("hops", static_cast<long long>(m.hops));
    case ring::decode_status::crc_error:
      return event(time_ns, "crc_error").number("hops", static_cast<long long>(m.hops)).number(
          "vr", static_cast<long long>(m.vr));
    case ring::decode_status::ok:
      break;
  }
  event e(time_ns, "message");
  switch (m.type) {
    case ring::message_type::character:
      e.text("type", "char").number("hops", static_cast<long long>(m.hops));
      e.text("text", std::string_view(reinterpret_cast<const char*>(m.text.data()), m.text.size()));
      break;
    case ring::message_type::variable: {
      char raw[24];
      std::snprintf(raw, sizeof raw, "0x%016" PRIx64, trionet::q32_to_raw(m.value));
      e.text("type", "var").number("hops", static_cast<long long>(m.hops)).number("vr", static_cast<long long>(m.vr));
      e.text("raw", raw).real("value", trionet::q32_to_double(m.value));
      break;
    }
    case ring::message_type::keypad_offset:
      e.text("type", "offset").number("hops", static_cast<long long>(m.hops)).number(
          "offset", static_cast<long long>(m.offset));
      break;
    case ring::message_type::keypad_mode:
      e.text("type", "mode").number("hops", static_cast<long long>(m.hops)).number(
          "mode", static_cast<long long>(m.mode));
      break;
  }
  return e;
}

event can_event(std::uint64_t time_ns, const can::frame& frame, std::uint8_t nodes) {
  const auto error = [&](const char* reason) {
    return event(time_ns, "error").text("reason", reason).text("frame", host::format_candump_frame(frame));
  };
  if (frame.extended() || frame.remote()) return error("unknown_id");
  const can::route_result route = can::route_of(nodes, frame.identifier());
  if (route.status != can::scheme_status::ok) return error("unknown_id");
  const can::decode_result decoded = can::decode_vr_frame(frame);
  if (!decoded) return error(can::to_string(decoded.status));
  const can::vr_message& message = decoded.message;
  event e(time_ns, "vr");
  e.number("id", static_cast<long long>(frame.identifier()));
  e.number("from", static_cast<long long>(route.value.sender)).number("to", static_cast<long long>(route.value.receiver));
  e.number("vr", static_cast<long long>(message.vr)).flag("negative", message.value.negative);
  e.number("int", static_cast<long long>(message.value.integer_part));
  e.number("frac", static_cast<long long>(message.value.fraction));
  e.real("value", trionet::to_double(message.value));
  return e;
}

std::string format(const event& e, bool json) {
  const auto seconds = static_cast<std::time_t>(e.time_ns / 1000000000u);
  const auto micros = static_cast<unsigned>(e.time_ns % 1000000000u / 1000u);
  std::string out;
  char stamp[40];
  if (json) {
    std::snprintf(stamp, sizeof stamp, "%lld.%06u", static_cast<long long>(seconds), micros);
    out = std::string("{\"time\":") + stamp + ",\"event\":" + json_string(e.name);
    for (const auto& [name, value] : e.fields) out += "," + json_string(name) + ":" + value;
    return out + "}";
  }
  std::tm local{};
  ::localtime_r(&seconds, &local);
  std::snprintf(stamp, sizeof stamp, "%02d:%02d:%02d.%06u", local.tm_hour, local.tm_min, local.tm_sec, micros);
  out = std::string(stamp) + " " + e.name;
  for (const auto& [name, value] : e.fields) out += " " + name + "=" + value;
  return out;
}

void emit(const event& e, bool json, std::FILE* to) {
  const std::string line = format(e, json) + "\n";
  std::fwrite(line.data(), 1, line.size(), to);
  std::fflush(to);
}

// ---- signals ----

namespace {

volatile std::sig_atomic_t stop_flag = 0;
volatile std::sig_atomic_t report_flag = 0;

extern "C" void on_stop(int) {
  stop_flag = 1;
}
extern "C" void on_report(int) {
  report_flag = 1;
}

constexpr int watched[5] = {SIGINT, SIGTERM, SIGHUP, SIGUSR1, SIGPIPE};

}  // namespace

signal_watch::signal_watch() {
  for (std::size_t i = 0; i < 5; ++i) {
    struct sigaction action {};
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;  // no SA_RESTART: poll() returns EINTR at once
    if (watched[i] == SIGUSR1) {
      action.sa_handler = on_report;
    } else if (watched[i] == SIGPIPE) {
      action.sa_handler = SIG_IGN;
    } else {
      action.sa_handler = on_stop;
    }
    ::sigaction(watched[i], &action, &old_[i]);
  }
}

signal_watch::~signal_watch() {
  for (std::size_t i = 0; i < 5; ++i) ::sigaction(watched[i], &old_[i], nullptr);
}

bool signal_watch::stop_requested() noexcept {
  return stop_flag != 0;
}

bool signal_watch::take_report_request() noexcept {
  if (report_flag == 0) return false;
  report_flag = 0;
  return true;
}

// ---- captures ----

bool capture_file::open(const std::string& path, std::string& error) {
  file_.open(path, std::ios::binary | std::ios::trunc);
  if (!file_) {
    error = "cannot write the capture " + path + ": " + std::strerror(errno);
    return false;
  }
  writer_ = std::make_unique<host::pcapng_writer>(file_);
  failed_ = writer_->flush() != host::pcapng_write_status::ok;
  return true;
}

std::uint32_t capture_file::add(const std::string& name, host::capture_network network) {
  if (!writer_) return 0;
  const host::pcapng_interface_result added = writer_->add_interface(name, network);
  failed_ = failed_ || !added || writer_->flush() != host::pcapng_write_status::ok;
  return added.id;
}

void capture_file::write(std::uint32_t interface, std::uint64_t time_ns, byte_view record) {
  if (!writer_ || failed_) return;
  failed_ = writer_->write(interface, time_ns, record) != host::pcapng_write_status::ok ||
            writer_->flush() != host::pcapng_write_status::ok;
}

// ---- command lines ----

bool line_reader::read_some() {
  char chunk[4096];
  const ssize_t got = ::read(fd_, chunk, sizeof chunk);
  if (got > 0) {
    for (ssize_t i = 0; i < got; ++i) {
      const char c = chunk[i];
      if (dropping_) {
        dropping_ = c != '\n';
      } else if (c == '\n') {
        pending_ += c;
        open_length_ = 0;
      } else if (open_length_ == max_line) {  // cut: what came so far is the line, its rest is dropped
        pending_ += '\n';
        open_length_ = 0;
        dropping_ = true;
      } else {
        pending_ += c;
        ++open_length_;
      }
    }
    return true;
  }
  if (got < 0 && (errno == EAGAIN || errno == EINTR)) return true;
  ended_ = true;
  if (!pending_.empty() && pending_.back() != '\n') pending_ += '\n';
  return false;
}

bool line_reader::next(std::string& line) {
  const std::size_t end = pending_.find('\n');
  if (end == std::string::npos) return false;
  line.assign(pending_, 0, end);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  pending_.erase(0, end + 1);
  return true;
}

std::vector<std::string> words_of(std::string_view line) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.emplace_back(line.substr(start, i - start));
  }
  return words;
}

bool unescape(std::string_view text, std::string& out, std::string& error) {
  out.clear();
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\\') {
      out += text[i];
      continue;
    }
    if (i + 1 >= text.size()) {
      error = "a lone \\ at the end of the text";
      return false;
    }
    const char c = text[++i];
    if (c == 'r') {
      out += '\r';
    } else if (c == 'n') {
      out += '\n';
    } else if (c == 't') {
      out += '\t';
    } else if (c == '\\') {
      out += '\\';
    } else if (c == 'x' && i + 2 < text.size() && std::isxdigit(static_cast<unsigned char>(text[i + 1])) &&
               std::isxdigit(static_cast<unsigned char>(text[i + 2]))) {
      out += static_cast<char>(std::stoi(std::string(text.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      error = std::string("unknown escape \\") + c + " (use \\r \\n \\t \\\\ \\xNN)";
      return false;
    }
  }
  return true;
}

}  // namespace trionet::cli::live
