// A Genius device on an Arm core, driven by its two interrupts while its main loop updates the turn data
// (qemu-system-arm -M lm3s6965evb; scripts/firmware-qemu-test runs it).
//
// The device (SBA 5, 153.6 kbaud standard: one skip time is one bit time) is driven exactly as
// firmware/programs/genius_node.cpp drives it, through platform/genius_link.hpp: a UART interrupt (the UART0
// vector: a word received, a start bit detected) and a timer interrupt (the TIMER0A vector: its one-shot
// timer expired), both at one priority. QEMU has no 9-bit UART, and its UART and timers are not in step at
// the resolution of one bit, so the hardware around the device is a model: SysTick, one interrupt per bit
// time, is the bus. It shifts 11-bit characters onto the wire one bit per tick, reports each start bit and
// each received word to the device's UART registers and raises the UART interrupt through the NVIC, counts
// the device's one-shot timer down and raises the timer interrupt when it expires, starts a word the device
// wrote at the next tick, and plays the other devices: a bus controller at SBA 31 (each scan: a transmission
// of two blocks, outputs for SBA 5 and SBA 3) and a device at SBA 3 (each turn: its inputs as a broadcast, or
// every fourth turn a transmission directed to SBA 5; one in seven with a data bit flipped, a CRC-6 error,
// and one in eleven of the others with its last data character received with a framing error). The bus takes
// no step while an interrupt it raised has not been served, so the run does not depend on how fast QEMU runs;
// its reload changes every tick (a pseudo-random 20..83 cycles), so that it preempts the main loop at ever
// different instructions.
//
// Checked on the wire (the bus interrupt, with the library's transmission parser): every transmission of SBA
// 5 starts at the tick its turn is due, (5 - s) mod 32 skip times after the end of the Stop of SBA s, plus
// the one tick a UART takes to start a word written to it; it is its turn data as the main loop set it (8
// bytes: a number and its complement, never torn, never going back) or the directed transmission the main
// loop queued (to SBA 3, each once, in order); no collision. Checked by the main loop: every block the
// controller sent to SBA 5 delivered once, in order, and none for SBA 3; every transmission of SBA 3 without
// an error delivered (broadcast or directed, in order), none with one; at the end the device's counters agree
// (turns taken, transmissions sent, CRC and framing errors; no collision, loss or overflow) and the last turn
// carried the main loop's last turn data.
//
// With TRIONET_GENIUS_TEST_BROKEN=1 the model's timer runs one tick longer than asked (a driver that starts
// the turn timer late): that image must fail, which shows that the timing is checked.
//
// Output through semihosting: the counts, "FAIL ..." for each broken check, then "trionet-genius-test: PASS"
// or "trionet-genius-test: FAIL"; qemu exits with 0 on pass, 1 on a failure, 2 on a fault.
#include <cstddef>
#include <cstdint>

#include "board.hpp"
#include "genius_link.hpp"
#include "semihosting.hpp"
#include "trionet/genius/device.hpp"
#include "trionet/genius/transmission.hpp"

#ifndef TRIONET_GENIUS_TEST_BROKEN
#define TRIONET_GENIUS_TEST_BROKEN 0
#endif

namespace {

namespace genius = trionet::genius;

constexpr std::uint8_t own_sba = 5;
constexpr std::uint8_t controller_sba = 31;
constexpr std::uint8_t other_sba = 3;
constexpr std::uint32_t scans = 200;            // the controller's transmissions in a run
constexpr std::uint32_t directed_to_send = 40;  // directed transmissions the main loop queues
constexpr unsigned timer_irq = 19;              // TIMER0A on the LM3S6965

genius::device<> node(own_sba, genius::bit_timing(genius::rate::standard_153k6));

void pend(unsigned irq) {
  board::reg(0xE000E200u + 4u * (irq / 32u)) = 1u << (irq % 32u);
}  // NVIC ISPR
void unpend(unsigned irq) {
  board::reg(0xE000E280u + 4u * (irq / 32u)) = 1u << (irq % 32u);
}  // NVIC ICPR

// ---- the hardware model: the device's UART registers and one-shot timer (the bus and the handlers only)
// ----
struct uart_model {
  std::uint16_t received = 0;  // the receive register
  bool full = false;           // a word waits in it
  bool framing_error = false;  // ... received with a framing error
  bool start_bit = false;      // a start bit was detected
  std::uint16_t to_send = 0;   // the transmit register
  bool sending = false;        // a word waits in it
} uart;

struct timer_model {
  std::uint32_t count = 0;
  bool running = false;
  bool fired = false;  // its interrupt raised and not yet served
} timer;

// ---- shared by the bus interrupt (writer) and the main loop ----
volatile std::uint32_t link_failures = 0;
const char* volatile link_failure = nullptr;
volatile std::uint32_t scans_sent = 0;       // the controller's transmissions sent whole
volatile std::uint32_t other_sent = 0;       // SBA 3's transmissions sent whole
volatile std::uint32_t other_corrupted = 0;  // ... of them with a data bit flipped
volatile std::uint32_t other_framing = 0;    // ... of them with a framing error on a character
volatile std::uint32_t own_seen = 0;         // SBA 5's transmissions seen whole on the wire
volatile std::uint32_t directed_seen = 0;    // ... of them directed to SBA 3
volatile std::uint32_t last_turn_data = 0;   // the number the last turn-data transmission of SBA 5 carried
volatile std::uint32_t ticks = 0;            // bit times
volatile std::uint32_t stalls = 0;           // ticks the bus waited for a handler
volatile bool bus_done = false;

void link_fail(const char* what) {
  if (link_failures == 0) link_failure = what;
  link_failures = link_failures + 1;
}

struct model_hardware {
  static firmware::uart_events uart_events() noexcept {
    firmware::uart_events events;
    events.received = uart.full;
    events.framing_error = uart.framing_error;
    events.start_bit = uart.start_bit;
    uart.start_bit = false;
    return events;
  }
  static std::uint16_t uart_read() noexcept {
    uart.full = false;
    return uart.received;
  }
  static void uart_write(std::uint16_t word) noexcept {
    if (uart.sending) link_fail("a word written while the transmit register was full");
    uart.to_send = word;
    uart.sending = true;
  }
  static void timer_start(std::uint32_t count,
                          bool /*from_end_of_character: the model reports a word at it*/) noexcept {
    timer.count = count + (TRIONET_GENIUS_TEST_BROKEN ? 1u : 0u);
    timer.running = count != 0;
    timer.fired = false;
    unpend(timer_irq);
  }
  static void timer_stop() noexcept {
    timer.running = false;
    timer.fired = false;
    unpend(timer_irq);  // a timer interrupt raised in the same tick as the start bit that cancels it
  }
};

using link = firmware::genius_link<genius::device<>, model_hardware>;

// ---- the other devices ----
std::uint32_t lcg = 2024;
std::uint32_t next_random() {
  lcg = lcg * 1664525u + 1013904223u;
  return lcg >> 8;
}

struct player {
  std::uint8_t sba;
  std::uint16_t words[24];
  std::size_t length = 0;
  std::size_t at = 0;
  std::uint32_t turns = 0;
  std::size_t framing_error_at = 0;  // the character received with a framing error (none: `length`)
};
player bus_controller{controller_sba, {}, 0, 0, 0, 0};
player sba3{other_sba, {}, 0, 0, 0, 0};

void encode(player& p, const genius::transmission& t, bool corrupt) {
  genius::character characters[24];
  const genius::encode_result r =
      genius::encode_transmission(trionet::span<genius::character>(characters, 24), t);
  if (!r) link_fail("a test transmission did not encode");
  for (std::size_t k = 0; k < r.length; ++k) p.words[k] = genius::to_uart_word(characters[k]);
  if (corrupt)
    p.words[r.length - 2] = static_cast<std::uint16_t>(p.words[r.length - 2] ^ 0x2u);  // last data byte
  p.length = r.length;
  p.at = 0;
  p.framing_error_at = r.length;
}

// The controller's scan k: a block of 4 bytes (k) for SBA 5, a block of 2 bytes for SBA 3.
void make_scan(std::uint32_t k) {
  const std::uint8_t outputs5[4] = {static_cast<std::uint8_t>(k), static_cast<std::uint8_t>(k >> 8),
                                    static_cast<std::uint8_t>(k >> 16), static_cast<std::uint8_t>(k >> 24)};
  const std::uint8_t outputs3[2] = {0xEE, static_cast<std::uint8_t>(k)};
  const genius::segment blocks[2] = {{true, own_sba, trionet::byte_view(outputs5, 4)},
                                     {true, other_sba, trionet::byte_view(outputs3, 2)}};
  encode(bus_controller, genius::transmission{controller_sba, true, 0, blocks}, false);
}

// SBA 3's turn j: a broadcast of 2 bytes (j), or every fourth a transmission directed to SBA 5 of 3 bytes.
void make_other(std::uint32_t j) {
  const std::uint8_t data[3] = {static_cast<std::uint8_t>(j), static_cast<std::uint8_t>(j >> 8), 0xA5};
  const bool directed = j % 4 == 1;
  const genius::segment plain[1] = {{false, 0, trionet::byte_view(data, directed ? 3 : 2)}};
  const bool corrupt = j % 7 == 3;
  encode(sba3, genius::transmission{other_sba, !directed, own_sba, plain}, corrupt);
  if (corrupt) other_corrupted = other_corrupted + 1;
  if (!corrupt && j % 11 == 6) {  // the last data character comes with a framing error (a noisy line)
    sba3.framing_error_at = sba3.length - 2;
    other_framing = other_framing + 1;
  }
}

// ---- the wire ----
enum class who : std::uint8_t { nobody, device, controller, other };
who talker = who::nobody;  // whose character is on the wire
std::uint16_t word_on_wire = 0;
bool framing_error_on_wire = false;  // the device's UART will see that character with a framing error
unsigned bit = 0;                    // of the character on the wire, 0 (start) .. 10 (stop)
std::uint32_t stop_end = 0;          // the tick at which the last Stop ended
std::uint8_t stop_sender = controller_sba;
bool started_since_stop = false;  // a transmission began after that Stop
player* due_player = nullptr;     // the other device whose turn comes next, at `due_tick`
std::uint32_t due_tick = 0;
std::uint32_t own_due_tick = 0;  // when SBA 5's turn comes
genius::transmission_parser<64, 8> monitor;
std::uint32_t expected_directed = 0;

// When `sba`'s turn comes after the last Stop (its own: a whole round later), with the tick the UART takes to
// start a word written to it. One skip time is one bit time.
std::uint32_t turn_tick(std::uint8_t sba) {
  const unsigned offset = genius::sba_offset(stop_sender, sba);
  return stop_end + (offset == 0 ? 32u : offset) + 1u;
}

void after_stop(std::uint8_t sender, std::uint32_t end) {
  stop_end = end;
  stop_sender = sender;
  started_since_stop = false;
  own_due_tick = turn_tick(own_sba);
  const std::uint32_t controller_due = turn_tick(controller_sba);
  const std::uint32_t other_due = turn_tick(other_sba);
  due_player = nullptr;
  if (scans_sent < scans) {
    due_player = controller_due < other_due ? &bus_controller : &sba3;
    due_tick = controller_due < other_due ? controller_due : other_due;
  }
}

// A whole transmission seen on the wire.
void seen(const genius::transmission& t) {
  if (t.sender != own_sba) return;
  own_seen = own_seen + 1;
  if (t.segments.size() != 1 || t.segments[0].block) {
    link_fail("SBA 5 sent something other than one run of plain data");
    return;
  }
  const trionet::byte_view d = t.segments[0].data;
  if (t.broadcast) {
    if (d.size() != 8) {
      link_fail("SBA 5's turn data is not 8 bytes");
      return;
    }
    const std::uint32_t n =
        d[0] | std::uint32_t{d[1]} << 8 | std::uint32_t{d[2]} << 16 | std::uint32_t{d[3]} << 24;
    const std::uint32_t m =
        d[4] | std::uint32_t{d[5]} << 8 | std::uint32_t{d[6]} << 16 | std::uint32_t{d[7]} << 24;
    if (m != ~n) link_fail("SBA 5's turn data torn");
    if (n < last_turn_data) link_fail("SBA 5's turn data went back");
    last_turn_data = n;
  } else {
    if (t.destination != other_sba || d.size() != 3 || d[0] != static_cast<std::uint8_t>(expected_directed) ||
        d[1] != static_cast<std::uint8_t>(expected_directed ^ 0x5Au) || d[2] != 0xD1) {
      link_fail("SBA 5's directed transmission is not the next one queued");
    }
    ++expected_directed;
    directed_seen = expected_directed;
  }
}

// A character ended: to the device's UART, and to the monitor.
void character_ended(who from, std::uint16_t word) {
  uart.received = word;
  uart.full = true;
  uart.framing_error = framing_error_on_wire;
  pend(board::uart0::irq);
  const genius::parse_status s = monitor.push(genius::from_uart_word(word));
  if (s == genius::parse_status::ok) seen(monitor.received());
  const genius::character c = genius::from_uart_word(word);
  // A Stop (control, tag 1 in the default layout): its sender is the one whose Start began it.
  const bool stop = c.control && genius::read_control(c.byte).kind == genius::control_kind::stop;
  if (genius::is_error(s) && !(from == who::other && s == genius::parse_status::stop_crc_mismatch)) {
    link_fail("a wire error other than the CRC errors put there on purpose");
  }
  if (!stop) return;
  if (from == who::controller) {
    scans_sent = scans_sent + 1;
    if (scans_sent == scans) bus_done = true;  // the last scan: the bus stops here
  }
  if (from == who::other) other_sent = other_sent + 1;
  after_stop(from == who::device ? own_sba : from == who::controller ? controller_sba : other_sba, ticks);
}

void start_word(who from, std::uint16_t word, bool framing_error = false) {
  talker = from;
  framing_error_on_wire = framing_error;
  word_on_wire = word;
  bit = 0;
  uart.start_bit = true;
  pend(board::uart0::irq);
}

}  // namespace

// The bus: one bit time per interrupt.
extern "C" void SysTick_Handler() {
  if (bus_done) {
    board::systick::stop();
    return;
  }
  board::systick::start(20u + (next_random() & 0x3Fu));  // the next tick somewhere else in the main loop
  if (uart.full || uart.start_bit || timer.fired) {      // a handler has not run yet: the bus waits for it
    stalls = stalls + 1;
    return;
  }
  ticks = ticks + 1;
  if (timer.running && --timer.count == 0) {
    timer.running = false;
    timer.fired = true;
    pend(timer_irq);
  }
  if (talker != who::nobody) {
    if (++bit == 10) {
      const who from = talker;
      talker = who::nobody;
      character_ended(from, word_on_wire);
    }
    return;
  }
  // The wire is idle: a word the device wrote, the next word of a transmission under way, or a turn due.
  player* next = bus_controller.at < bus_controller.length ? &bus_controller
                 : sba3.at < sba3.length                   ? &sba3
                                                           : nullptr;
  if (uart.sending) {
    if (next != nullptr) link_fail("SBA 5 sent inside another device's transmission");
    if (!started_since_stop && ticks != own_due_tick) link_fail("SBA 5 took its turn at the wrong time");
    if (due_player != nullptr && started_since_stop == false && due_tick < ticks) {
      link_fail("SBA 5 took another device's turn");
    }
    started_since_stop = true;
    uart.sending = false;
    start_word(who::device, uart.to_send);
    return;
  }
  if (!started_since_stop && ticks == own_due_tick + 1 && own_due_tick < due_tick) {
    link_fail("SBA 5 let its turn pass");
  }
  if (next == nullptr && due_player != nullptr && !started_since_stop && ticks == due_tick) {
    next = due_player;
    if (next == &bus_controller) {
      make_scan(bus_controller.turns++);
    } else {
      make_other(sba3.turns++);
    }
  }
  if (next != nullptr) {
    started_since_stop = true;
    const bool framing_error = next->at == next->framing_error_at;
    start_word(next == &bus_controller ? who::controller : who::other, next->words[next->at++],
               framing_error);
    return;
  }
}

extern "C" void UART0_IRQHandler() {
  link::uart_interrupt(node);
}
extern "C" void TIMER0A_IRQHandler() {
  link::timer_interrupt(node);
}

extern "C" void HardFault_Handler() {
  semihosting::write("trionet-genius-test: FAIL (hard fault)\n");
  semihosting::exit(2);
}

int main() {
  semihosting::write("trionet-genius-test: start (Cortex-M3, lm3s6965evb)\n");
  std::uint32_t failures = 0;
  auto fail = [&failures](const char* what) {
    if (failures < 8) {
      semihosting::write("FAIL ");
      semihosting::write(what);
      semihosting::write("\n");
    }
    ++failures;
  };

  std::uint32_t n = 0;           // the turn data's number
  std::uint32_t queued = 0;      // directed transmissions queued
  std::uint32_t blocks = 0;      // blocks delivered (from the controller: k = 0, 1, ...)
  std::uint32_t from_other = 0;  // SBA 3's transmissions delivered
  std::uint32_t last_other = 0;  // ... the last one's number + 1
  std::uint32_t reads = 0;
  bool frozen = false;  // the turn data no longer changes (the end of the run)
  auto set_turn_data = [&]() {
    const std::uint32_t m = ~n;
    const std::uint8_t data[8] = {static_cast<std::uint8_t>(n),       static_cast<std::uint8_t>(n >> 8),
                                  static_cast<std::uint8_t>(n >> 16), static_cast<std::uint8_t>(n >> 24),
                                  static_cast<std::uint8_t>(m),       static_cast<std::uint8_t>(m >> 8),
                                  static_cast<std::uint8_t>(m >> 16), static_cast<std::uint8_t>(m >> 24)};
    if (node.set_turn_data(trionet::byte_view(data, 8)) != genius::turn_data_status::ok)
      fail("set_turn_data");
  };

  board::nvic::enable(board::uart0::irq);  // the interrupts the bus raises (priority 0, as SysTick's)
  board::nvic::enable(timer_irq);
  node.deliver_broadcasts_from(1u << other_sba);
  set_turn_data();
  link::power_on(node);
  // Power-up: the bus is quiet, so every device acts as if the Stop of SBA 31 had ended 32 skip times + 2
  // characters later (the idle restart): the device by its own timer, the others here.
  after_stop(controller_sba, 32u + 2u * 11u);
  board::systick::start(400);

  while (!bus_done) {
    if (!frozen) {
      ++n;
      set_turn_data();
      if (scans_sent + 4 >= scans) frozen = true;  // a few more turns carry the last number
    }
    if (queued < directed_to_send && node.directed_waiting() == 0 && (n & 15u) == 0) {
      const std::uint8_t data[3] = {static_cast<std::uint8_t>(queued),
                                    static_cast<std::uint8_t>(queued ^ 0x5Au), 0xD1};
      if (node.queue_directed(other_sba, trionet::byte_view(data, 3)) == genius::queue_status::ok) {
        ++queued;
      } else {
        fail("queue_directed refused with a free slot");
      }
    }
    std::uint8_t data[genius::device<>::delivery_capacity];
    const genius::delivery_result got = node.read(trionet::byte_buffer(data, sizeof data));
    if (!got) continue;
    ++reads;
    if (got.kind == genius::delivery_kind::block) {
      const std::uint32_t k =
          data[0] | std::uint32_t{data[1]} << 8 | std::uint32_t{data[2]} << 16 | std::uint32_t{data[3]} << 24;
      if (got.sender != controller_sba || got.length != 4 || k != blocks)
        fail("a block out of order or not ours");
      ++blocks;
    } else {
      const std::uint32_t j = data[0] | std::uint32_t{data[1]} << 8;
      const bool directed = got.kind == genius::delivery_kind::directed;
      if (got.sender != other_sba || got.length != (directed ? 3u : 2u) || (directed && data[2] != 0xA5) ||
          (j % 4 == 1) != directed || j % 7 == 3 || j % 11 == 6 || (from_other != 0 && j < last_other)) {
        fail("a delivery from SBA 3 that is wrong, out of order, or had a CRC or framing error");
      }
      last_other = j + 1;
      ++from_other;
    }
  }

  // The bus has stopped: what the device delivered is all there.
  for (;;) {
    std::uint8_t data[genius::device<>::delivery_capacity];
    const genius::delivery_result got = node.read(trionet::byte_buffer(data, sizeof data));
    if (!got) break;
    ++reads;
    if (got.kind == genius::delivery_kind::block) {
      ++blocks;
    } else {
      ++from_other;
    }
  }
  const genius::device_counters c = node.counters();
  semihosting::report("bit times ", ticks);
  semihosting::report("bus ticks that waited for a handler ", stalls);
  semihosting::report("scans (controller transmissions) ", scans_sent);
  semihosting::report("SBA 3 transmissions ", other_sent);
  semihosting::report("SBA 3 transmissions with a data bit flipped (CRC errors) ", other_corrupted);
  semihosting::report("SBA 3 transmissions with a framing error ", other_framing);
  semihosting::report("SBA 5 transmissions seen on the wire ", own_seen);
  semihosting::report("SBA 5 directed transmissions seen on the wire ", directed_seen);
  semihosting::report("turn data updates by the main loop ", n);
  semihosting::report("deliveries read ", reads);
  semihosting::report("turns taken ", c.turns_taken);
  semihosting::report("turns passed ", c.turns_passed);
  semihosting::report("idle restarts ", c.idle_restarts);
  if (blocks != scans_sent) fail("not every block for SBA 5 was delivered");
  if (from_other != other_sent - other_corrupted - other_framing) {
    fail("not every good transmission of SBA 3 was delivered");
  }
  if (directed_seen != queued || queued != directed_to_send) fail("not every directed transmission was sent");
  if (last_turn_data != n) fail("the last turn did not carry the last turn data");
  if (c.turns_taken != own_seen || c.transmissions_sent != own_seen) fail("turns taken or sent != seen");
  if (c.crc_errors != other_corrupted) fail("CRC errors counted != put in");
  if (c.framing_errors != other_framing) fail("framing errors counted != put in");
  if (c.collisions != 0 || c.lost_transmissions != 0 || c.wire_errors != 0 || c.delivery_overflows != 0) {
    fail("a collision, loss, wire error or overflow counted");
  }
  if (c.deliveries != reads) fail("deliveries counted != read");
  if (c.idle_restarts != 1 || c.turns_passed != 0)
    fail("idle restarts other than at power-up, or a turn passed");
  if (own_seen < scans - 1) fail("SBA 5 did not take a turn in every scan");
  if (link_failures != 0) {
    semihosting::write("FAIL (bus) ");
    semihosting::write(link_failure);
    semihosting::write("\n");
  }
  if (failures != 0 || link_failures != 0) {
    semihosting::write("trionet-genius-test: FAIL\n");
    semihosting::exit(1);
  }
  semihosting::write("trionet-genius-test: PASS\n");
  semihosting::exit(0);
}
