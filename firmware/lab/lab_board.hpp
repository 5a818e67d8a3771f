// What the lab's board programs (master.cpp, axis.cpp) share: a Motion Coordinator's ring link driven by
// interrupts on the emulated TI LM3S6965 (qemu-system-arm -M lm3s6965evb), a debug console, the program's
// time, and the board's settings. docs/firmware.md ("From the lab to a real board") says what each piece
// becomes on real hardware.
//
//   UART0 (PL011 at 0x4000C000, IRQ 5)   the ring link: the node's link side. Each interrupt takes every
//                                         received byte (`receive`) and fills the transmitter (`transmit`);
//                                         the transmit interrupt is switched off when the node has nothing
//                                         to send. The program side starts a transmission by setting the
//                                         interrupt pending (a PL011 raises its transmit interrupt only after
//                                         a byte was written).
//   SysTick (100 Hz, the same priority)   the program's time (`ticks`) and the idle line (docs/protocol.md
//                                         1.10): a message open at the node while `idle_ticks` ticks pass
//                                         without a byte is ended with `line_idle()`. QEMU's PL011 has no
//                                         receive-timeout interrupt (its RTIM bit is never raised), so the
//                                         timer does what an idle-line interrupt does on other UARTs. Both
//                                         interrupts have priority 0: they never preempt each other, so the
//                                         link side is one context (docs/design.md, "Contexts").
//   UART1 (PL011 at 0x4000D000, IRQ 6)   the debug console: a line in, a line out (counters, NETSTAT).
//   semihosting SYS_GET_CMDLINE          the board's settings as words key=value (qemu's
//                                         -semihosting-config arg=...): a real board has them as constants
//                                         or in its configuration store.
//
// The wire parameters come from lab_profile.hpp, written by `trionet profile header --namespace lab_profile`.
// Cost: the node (profile's capacities), a VR table of the program's size, 2 KiB of logs and buffers.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "board.hpp"
#include "lab_profile.hpp"
#include "semihosting.hpp"
#include "trionet/q32.hpp"
#include "trionet/vr.hpp"

namespace lab {

namespace ring = trionet::ring;

// ---- PL011 UARTs ----

/// One PL011 UART: registers at `base`, interrupt `irq`.
struct uart {
  std::uintptr_t base;
  unsigned irq;

  volatile std::uint32_t& data() const noexcept { return board::reg(base + 0x00u); }         // DR
  volatile std::uint32_t& flags() const noexcept { return board::reg(base + 0x18u); }        // FR
  volatile std::uint32_t& mask() const noexcept { return board::reg(base + 0x38u); }         // IMSC
  bool rx_ready() const noexcept { return (flags() & (1u << 4)) == 0; }                      // !RXFE
  bool tx_ready() const noexcept { return (flags() & (1u << 5)) == 0; }                      // !TXFF
  std::uint8_t read() const noexcept { return static_cast<std::uint8_t>(data() & 0xFFu); }
  void write(std::uint8_t byte) const noexcept { data() = byte; }

  static constexpr std::uint32_t rx_interrupts = (1u << 4) | (1u << 6);  // RXIM, RTIM
  static constexpr std::uint32_t tx_interrupt = 1u << 5;                 // TXIM

  /// 8N1 with the FIFOs on; receive (and receive-timeout) interrupts on.
  void start() const noexcept {
    board::reg(base + 0x2Cu) = 0x70u;  // LCRH: 8 data bits, FIFOs enabled
    mask() = rx_interrupts;
    board::reg(base + 0x30u) = 0x301u;  // CR: UARTEN, TXE, RXE
    board::nvic::enable(irq);
  }
  /// The transmit interrupt on (program side, after queuing) or off (the interrupt, when nothing is left).
  /// The read-modify-write from both sides is safe as used: see board::uart0::enable_tx_interrupt.
  void transmit_interrupt(bool on) const noexcept {
    if (on) {
      mask() |= tx_interrupt;
    } else {
      mask() &= ~tx_interrupt;
    }
  }
  /// Makes the interrupt pending: its handler runs as soon as the priorities allow.
  void pend() const noexcept { board::reg(0xE000E200u + 4u * (irq / 32u)) = 1u << (irq % 32u); }
};

inline constexpr uart ring_uart{0x4000C000u, 5};
inline constexpr uart debug_uart{0x4000D000u, 6};

// ---- time ----

/// SysTick at 100 Hz: the LM3S6965's SysTick counts the 12 MHz core clock that QEMU models for it.
constexpr std::uint32_t core_clock_hz = 12000000;
constexpr std::uint32_t ticks_per_second = 100;
constexpr std::uint32_t ms_per_tick = 1000 / ticks_per_second;

// ---- settings ----

/// The board's settings: the words "key=value" of the semihosting command line.
class settings {
 public:
  /// Reads the command line once (SYS_GET_CMDLINE).
  void load() noexcept {
    struct {
      char* buffer;
      std::uint32_t length;
    } block{text_, sizeof text_ - 1};
    if (semihosting::call(0x15, &block) != 0) block.length = 0;  // SYS_GET_CMDLINE failed: no settings
    text_[block.length < sizeof text_ ? block.length : sizeof text_ - 1] = '\0';
  }
  /// The value of `key` as a number, or `otherwise`.
  int number(const char* key, int otherwise) const noexcept {
    const char* v = find(key);
    return v == nullptr ? otherwise : parse(v);
  }
  /// The `index`-th number of a list separated by colons (`axes=10:11`: a comma would end qemu's option), or 0.
  int list_item(const char* key, unsigned index) const noexcept {
    const char* v = find(key);
    for (unsigned i = 0; v != nullptr && i < index; ++i) {
      while (*v != '\0' && *v != ' ' && *v != ':') ++v;
      v = *v == ':' ? v + 1 : nullptr;
    }
    return v == nullptr ? 0 : parse(v);
  }

 private:
  const char* find(const char* key) const noexcept {
    const std::size_t length = std::strlen(key);
    for (const char* p = text_; *p != '\0';) {
      while (*p == ' ') ++p;
      if (std::strncmp(p, key, length) == 0 && p[length] == '=') return p + length + 1;
      while (*p != '\0' && *p != ' ') ++p;
    }
    return nullptr;
  }
  static int parse(const char* v) noexcept {
    int n = 0;
    while (*v >= '0' && *v <= '9') n = n * 10 + (*v++ - '0');
    return n;
  }

  char text_[256] = {};
};

// ---- text ----

/// A line of text built in place (no heap, no printf).
class line {
 public:
  line& add(const char* text) noexcept {
    while (*text != '\0' && length_ < sizeof text_ - 1) text_[length_++] = *text++;
    text_[length_] = '\0';
    return *this;
  }
  line& add(char c) noexcept {
    if (length_ < sizeof text_ - 1) text_[length_++] = c;
    text_[length_] = '\0';
    return *this;
  }
  line& number(std::uint32_t value) noexcept {
    char digits[10];
    unsigned n = 0;
    do {
      digits[n++] = static_cast<char>('0' + value % 10);
      value /= 10;
    } while (value != 0);
    while (n != 0) add(digits[--n]);
    return *this;
  }
  /// " key=value"
  line& field(const char* key, std::uint32_t value) noexcept { return add(' ').add(key).add('=').number(value); }
  /// A Q32.32 value with `decimals` decimals (0..4), rounded half away from zero, right-aligned in `width`
  /// characters (BASIC's VR(n)[w.d]).
  line& fixed(std::int64_t raw, unsigned width, unsigned decimals) noexcept {
    const bool negative = raw < 0;
    const std::uint64_t magnitude = negative ? 0u - static_cast<std::uint64_t>(raw) : static_cast<std::uint64_t>(raw);
    std::uint32_t scale = 1;
    for (unsigned i = 0; i < decimals; ++i) scale *= 10;
    // The integer part and the fraction apart: no 64-bit overflow for any Q32.32 value.
    std::uint64_t whole = magnitude >> 32;
    std::uint64_t part = ((magnitude & 0xFFFFFFFFu) * scale + 0x80000000u) >> 32;
    if (part >= scale) {
      part -= scale;
      ++whole;
    }
    char digits[24];
    unsigned n = 0;
    for (unsigned i = 0; i < decimals; ++i) {
      digits[n++] = static_cast<char>('0' + part % 10);
      part /= 10;
    }
    if (decimals != 0) digits[n++] = '.';
    do {
      digits[n++] = static_cast<char>('0' + whole % 10);
      whole /= 10;
    } while (whole != 0 && n < sizeof digits - 1);
    if (negative && (magnitude >> 32 != 0 || part != 0 || (magnitude & 0xFFFFFFFFu) != 0)) digits[n++] = '-';
    for (unsigned pad = n; pad < width; ++pad) add(' ');
    while (n != 0) add(digits[--n]);
    return *this;
  }
  /// CURSOR(p): escape, 'H', then the position on the wire (p plus the display's position base).
  line& cursor(unsigned position) noexcept {
    return add('\x1b').add('H').add(static_cast<char>(position + lab_profile::keypad_display_model.position_base));
  }

  [[nodiscard]] const char* text() const noexcept { return text_; }
  [[nodiscard]] std::size_t size() const noexcept { return length_; }
  void clear() noexcept {
    length_ = 0;
    text_[0] = '\0';
  }

 private:
  char text_[1024] = {};
  std::size_t length_ = 0;
};

// ---- VR(), with every accepted network write logged for the program ----

/// One VR written by the network.
struct vr_write {
  std::uint16_t vr;
  std::int64_t value;  // Q32.32
};

/// VR() of `Size` Q32.32 variables behind the program's write policy (`owns`: the VRs this board owns,
/// docs/protocol.md 1.6); each accepted write is also queued for the program, which may answer it. Link side:
/// `write`; program side: `take`, `get`, `set`. A write that finds the log full is applied but not queued,
/// and counted (`log_overflows`).
template <std::size_t Size, std::size_t LogCapacity = 64>
class logged_vrs final : public trionet::vr_store {
  static_assert((LogCapacity & (LogCapacity - 1)) == 0, "the log's capacity is a power of two");

 public:
  using owner_policy = bool (*)(std::uint16_t vr) noexcept;

  explicit logged_vrs(owner_policy owns) noexcept : owns_(owns), table_(&policy, this) {}

  [[nodiscard]] trionet::vr_write_status write(std::uint16_t vr, const trionet::network_value& value) noexcept override {
    const trionet::vr_write_status status = table_.write(vr, value);
    if (status != trionet::vr_write_status::ok) return status;
    const std::uint32_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) == LogCapacity) {
      log_overflows_.store(log_overflows_.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
      return status;
    }
    log_[head % LogCapacity] = {vr, table_.get(vr)};
    head_.store(head + 1, std::memory_order_release);
    return status;
  }

  /// Program side: the oldest logged write; false if none.
  bool take(vr_write& out) noexcept {
    const std::uint32_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    out = log_[tail % LogCapacity];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  std::int64_t get(std::size_t vr) const noexcept { return table_.get(vr); }
  void set(std::size_t vr, std::int64_t value) noexcept { table_.set(vr, value); }
  std::uint32_t log_overflows() const noexcept { return log_overflows_.load(std::memory_order_relaxed); }

 private:
  static bool policy(void* context, std::uint16_t vr, std::int64_t) noexcept {
    return static_cast<const logged_vrs*>(context)->owns_(vr);
  }

  owner_policy owns_;
  trionet::vr_table<Size, std::int64_t> table_;
  vr_write log_[LogCapacity] = {};
  std::atomic<std::uint32_t> head_{0};  // written by the link side
  std::atomic<std::uint32_t> tail_{0};  // written by the program side
  std::atomic<std::uint32_t> log_overflows_{0};
};

// ---- the ring link ----

/// What the link side counted (each written by the interrupts only; the program reads them whole).
struct link_statistics {
  volatile std::uint32_t uart_interrupts = 0;
  volatile std::uint32_t bytes_received = 0;
  volatile std::uint32_t bytes_sent = 0;
  volatile std::uint32_t idle_lines = 0;  // line_idle() calls (a message was open)
  volatile std::uint32_t ticks = 0;
};

/// The node's link side on UART0 and SysTick. `Node` is a ring node (motion_coordinator).
template <class Node>
class ring_link {
 public:
  explicit ring_link(Node& node) noexcept : node_(&node) {}

  /// Starts the UART and the 100 Hz tick; `idle_ticks` silent ticks with a message open are the idle line.
  void start(unsigned idle_ticks) noexcept {
    idle_ticks_ = idle_ticks < 2 ? 2 : idle_ticks;
    ring_uart.start();
    board::systick::start(core_clock_hz / ticks_per_second - 1);
  }

  /// UART0's interrupt (link side). A byte in, then what can go out, in turn: as a UART at line rate gives
  /// them. Taking every byte the receive FIFO holds before transmitting any would let a forwarded burst
  /// outgrow the forward buffer, and QEMU refills the FIFO while the handler runs.
  void uart_interrupt() noexcept {
    stats_.uart_interrupts = stats_.uart_interrupts + 1;
    std::uint32_t received = 0;
    while (ring_uart.rx_ready()) {
      node_->receive(ring_uart.read());
      ++received;
      transmit();
    }
    if (received != 0) stats_.bytes_received = stats_.bytes_received + received;
    transmit();
  }

  /// SysTick (link side: the same priority as UART0): the time, and the idle line.
  void tick_interrupt() noexcept {
    stats_.ticks = stats_.ticks + 1;
    const std::uint32_t received = stats_.bytes_received;
    if (received != seen_ || !node_->in_message()) {
      seen_ = received;
      quiet_ = 0;
      return;
    }
    if (++quiet_ < idle_ticks_) return;
    quiet_ = 0;
    node_->line_idle();
    stats_.idle_lines = stats_.idle_lines + 1;
    transmit();  // own messages held behind the open one may go now
  }

  /// Program side: after queuing a message, starts the transmitter.
  void kick() noexcept {
    ring_uart.transmit_interrupt(true);
    ring_uart.pend();
  }

  /// Program side: BASIC's SEND(n,1,vr,value), which waits: until the transmit queue has room for the frame
  /// (the link runs meanwhile), 2 s at most; only a queue still full then is refused (NETSTAT bit 0,
  /// docs/protocol.md 1.6).
  ring::send_status send(int n, std::uint16_t vr, std::int64_t value) noexcept {
    constexpr std::size_t frame = 16;  // a direct variable transfer (docs/protocol.md 1.3)
    const std::uint32_t since = ticks();
    while (node_->transmit_free() < frame && ticks() - since < 2 * ticks_per_second) {
      kick();
      board::wait_for_interrupt();
    }
    const ring::send_status status = node_->send_variable_q32(n, vr, value);
    kick();
    return status;
  }

  /// Program side: BASIC's PRINT #n,text, which waits for room as SEND does.
  ring::send_status print(int n, const line& text) noexcept {
    const std::uint32_t since = ticks();
    const ring::print_result r = node_->print_all(
        n, trionet::byte_view(reinterpret_cast<const std::uint8_t*>(text.text()), text.size()), [&]() noexcept {
          kick();
          board::wait_for_interrupt();
          return ticks() - since < 2 * ticks_per_second;
        });
    kick();
    return r.status;
  }

  /// Program side: the time in ticks (10 ms).
  std::uint32_t ticks() const noexcept { return stats_.ticks; }
  const link_statistics& statistics() const noexcept { return stats_; }

 private:
  void transmit() noexcept {
    std::uint32_t sent = 0;
    std::uint8_t byte = 0;
    while (ring_uart.tx_ready()) {
      if (!node_->transmit(byte)) {
        ring_uart.transmit_interrupt(false);  // nothing to send: the program side kicks it again
        break;
      }
      ring_uart.write(byte);
      ++sent;
    }
    if (sent != 0) stats_.bytes_sent = stats_.bytes_sent + sent;
  }

  Node* node_;
  link_statistics stats_;
  std::uint32_t seen_ = 0;
  unsigned quiet_ = 0;
  unsigned idle_ticks_ = 3;
};

// ---- the main loop's sleep ----

/// Set by every interrupt handler (`woken()`); the main loop sleeps only when none has run since its last
/// look (`sleep()`).
inline volatile bool interrupted = false;

/// Interrupt handlers: the main loop has something to look at.
inline void woken() noexcept { interrupted = true; }

/// Main loop: sleeps (WFI) until an interrupt has run since the last call. Interrupts are masked around the
/// check so that one arriving just before the WFI still ends it (a pending interrupt wakes a WFI even while
/// masked): the main loop never sleeps on work an interrupt left for it. Idle boards cost QEMU little CPU.
inline void sleep() noexcept {
  board::disable_interrupts();
  if (!interrupted) board::wait_for_interrupt();
  interrupted = false;
  board::enable_interrupts();
}

// ---- the debug console ----

/// UART1: the host sends one command line, the board answers with one line (program side). The interrupt
/// gathers the line; the program takes it with `take`.
class console {
 public:
  void start() noexcept { debug_uart.start(); }

  /// UART1's interrupt.
  void interrupt() noexcept {
    while (debug_uart.rx_ready()) {
      const char c = static_cast<char>(debug_uart.read());
      if (ready_) continue;  // the program has not taken the last line yet: the host waits for its answer
      if (c == '\n' || c == '\r') {
        if (length_ == 0) continue;
        command_[length_] = '\0';
        length_ = 0;
        ready_ = true;
      } else if (length_ < sizeof command_ - 1) {
        command_[length_++] = c;
      }
    }
  }

  /// Program side: the command line that arrived (copied into `out`), if one did.
  bool take(char (&out)[32]) noexcept {
    if (!ready_) return false;
    std::memcpy(out, const_cast<const char*>(command_), sizeof out);
    ready_ = false;
    return true;
  }

  /// Program side: writes `text` and a newline (polled: the host reads it at once).
  static void answer(const line& text) noexcept {
    for (std::size_t i = 0; i < text.size(); ++i) put(static_cast<std::uint8_t>(text.text()[i]));
    put('\n');
  }

 private:
  static void put(std::uint8_t byte) noexcept {
    while (!debug_uart.tx_ready()) {
    }
    debug_uart.write(byte);
  }

  volatile char command_[32] = {};
  volatile std::size_t length_ = 0;
  volatile bool ready_ = false;
};

/// The node's counters, NETSTAT and the link's statistics as fields of one line.
template <class Node, class Link>
void node_fields(line& out, const Node& node, const Link& link) {
  const ring::motion_coordinator_counters c = node.counters();
  const ring::link_counters f = node.forwarding_counters();
  const link_statistics& s = link.statistics();
  out.field("netstat", node.netstat());
  out.field("frame_errors", c.frame_errors).field("crc_errors", c.crc_errors);
  out.field("receive_overflows", c.receive_overflows).field("character_messages", c.character_messages);
  out.field("variables_written", c.variables_written).field("variables_refused", c.variables_refused);
  out.field("variables_out_of_range", c.variables_out_of_range);
  out.field("keypad_messages_ignored", c.keypad_messages_ignored).field("sends_refused", c.sends_refused);
  out.field("messages_forwarded", f.messages_forwarded).field("forwards_lost", f.forwards_lost);
  out.field("forwards_cut", f.forwards_cut).field("forwards_ended_idle", f.forwards_ended_idle);
  out.field("messages_dropped", f.messages_dropped).field("messages_sent", f.messages_sent);
  out.field("uart_interrupts", s.uart_interrupts).field("bytes_received", s.bytes_received);
  out.field("bytes_sent", s.bytes_sent).field("idle_lines", s.idle_lines).field("ticks", s.ticks);
}

}  // namespace lab
