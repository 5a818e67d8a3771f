// The lab's master board: the three-axis Motion Coordinator of the Trio manual's Example 2. It sets the
// keypad's offset, runs the machine's menu on the keypad's display (feed length and speed, then start),
// hands the settings to the two-axis board and starts it, and publishes its settings to a Motion Coordinator
// on the host. In the background it can ask every axis board for a VR answer at a steady rate (the lab's
// traffic across boards).
//
// Settings (semihosting command line, docs/firmware.md):
//   keypad=N    the keypad's BASIC address from this board
//   offset=M    the keypad offset to send: this board's BASIC address from the keypad (default 10)
//   axes=A:B:.. the axis boards' BASIC addresses; the first is Example 2's two-axis node
//   host=H      the host Motion Coordinator's BASIC address (0: none)
//   idle=T      ticks of 10 ms without a byte, with a message open, that make the idle line (default 3)
//   start=MS    wait MS milliseconds before the program starts (default 0), as the manual suggests for a
//               ring whose nodes power up together: the lab starts its programs on the host meanwhile
//
// The program follows Example 2 step by step (the manual's BASIC in the comments), with a few changes that
// a machine in use needs: the menu loops back to its GET, not to the label (which the manual's version
// prints again at the cursor); the speed and the prompts have fixed places on the display; "I" is sent again
// while the two-axis node does not answer (the ring may not be whole yet); after the start, the stop key
// returns to the menu.
//
// Debug console (UART1): "c" answers the counters, "n" clears NETSTAT, "p MS" asks the axes every MS ms
// (0: stop). One line back: "lab role=master ..." with key=value fields.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "lab_board.hpp"

namespace {

namespace ring = trionet::ring;

constexpr std::uint16_t feed_length_vr = 0;  // VR(0): feed length
constexpr std::uint16_t speed_vr = 1;        // VR(1): speed
constexpr std::uint16_t ready_vr = 200;      // VR(200): the two-axis node's handshake (99 ready, 999 running)
constexpr std::uint16_t poll_base_vr = 1000;  // VR(1000 + 100 (k - 1) + j): the axis k's answers
constexpr unsigned max_axes = 4;
constexpr std::uint16_t host_vr = 300;  // VR(300..302) on the host: feed length, speed, step

// GET#3 values (docs/protocol.md 1.8).
constexpr std::uint8_t key_up = 10;
constexpr std::uint8_t key_down = 11;
constexpr std::uint8_t key_yes = 13;
constexpr std::uint8_t key_start = 20;
constexpr std::uint8_t key_stop = 21;

constexpr std::int64_t one = std::int64_t{1} << 32;
constexpr std::int64_t tenth = trionet::q32_from_double(0.1).raw;
constexpr std::int64_t hundredth = trionet::q32_from_double(0.01).raw;

bool owns(std::uint16_t vr) noexcept {
  return vr == ready_vr || (vr >= poll_base_vr && vr < poll_base_vr + 100 * max_axes);
}

lab::logged_vrs<poll_base_vr + 100 * max_axes> vrs(owns);
lab_profile::motion_coordinator<> node(vrs, lab_profile::defkey);
lab::ring_link<decltype(node)> ring_link(node);
lab::console console;
lab::settings settings;

}  // namespace

extern "C" void UART0_IRQHandler() {
  ring_link.uart_interrupt();
  lab::woken();
}
extern "C" void SysTick_Handler() {
  ring_link.tick_interrupt();
  lab::woken();
}
extern "C" void UART1_IRQHandler() {
  console.interrupt();
  lab::woken();
}

namespace {

int keypad = 0;
int offset = 10;
std::uint32_t start_ticks = 0;
int host = 0;
int axes[max_axes] = {};
unsigned axis_count = 0;

// PRINT #n,text and SEND(n,1,vr,value), waiting for room as BASIC's do (n = 0: no such node).
void print(int n, const lab::line& text) {
  if (n != 0) static_cast<void>(ring_link.print(n, text));
}

void send(int n, std::uint16_t vr, std::int64_t value) {
  if (n != 0) static_cast<void>(ring_link.send(n, vr, value));
}

// ---- Example 2 ----

enum class step : std::uint8_t { init, wait_ready, feed_length, speed, press_start, wait_running, running };

step now = step::init;
std::uint32_t step_started = 0;
std::uint32_t ready_retries = 0;
std::uint32_t keys_read = 0;
std::int64_t published[3] = {-1, -1, -1};

void go(step next) {
  now = next;
  step_started = ring_link.ticks();
}

void show_feed_length() {
  lab::line t;
  t.cursor(32).fixed(vrs.get(feed_length_vr), 6, 1);  // PRINT#11,CHR(27);CHR(72);CHR(32);VR(0)[6.1];
  print(keypad, t);
}

void show_speed() {
  lab::line t;
  t.cursor(26).fixed(vrs.get(speed_vr), 6, 2);
  print(keypad, t);
}

void ask_ready() {
  static_cast<void>(node.send_keypad_offset(keypad, offset));  // init: SEND(11,2,10)
  lab::line t;
  t.add("\x0c\x0e").add("INITIALISING.....\r\n");  // PRINT #11,CHR(12);CHR(14);"INITIALISING....."
  print(keypad, t);
  t.clear();
  print(axes[0], t.add("I"));  // PRINT #10,"I";
}

void menu() {
  lab::line t;
  t.add("\x0c\x0e").add("MACHINE READY\r\n");  // PRINT #11,CHR(12);CHR(14);"MACHINE READY"
  t.add("FEED LENGTH:").fixed(vrs.get(feed_length_vr), 6, 1).add("  ");  // setlen: PRINT #11,"FEED LENGTH:";VR(0)[6.1];
  print(keypad, t);
  go(step::feed_length);
}

void program_step() {
  switch (now) {
    case step::init:
      if (ring_link.ticks() < start_ticks) return;
      ask_ready();
      go(step::wait_ready);
      return;
    case step::wait_ready:  // WAIT UNTIL VR(200)=99
      if (vrs.get(ready_vr) == 99 * one) {
        menu();
      } else if (ring_link.ticks() - step_started > 3 * lab::ticks_per_second) {
        ++ready_retries;
        ask_ready();
        go(step::wait_ready);
      }
      return;
    default:
      break;
  }
  const ring::get_result key = node.get(3);  // GET #3,VR(100)
  if (now == step::wait_running && vrs.get(ready_vr) == 999 * one) {  // WAIT UNTIL VR(200)=999
    lab::line t;
    t.add("\x0c\x0e").add("RUNNING\r\n").add("LEN").fixed(vrs.get(feed_length_vr), 6, 1);  // 19 characters
    t.add(" SPD").fixed(vrs.get(speed_vr), 6, 2);
    print(keypad, t);
    go(step::running);
  }
  if (!key) return;
  ++keys_read;
  const std::uint8_t k = key.value;
  switch (now) {
    case step::feed_length:
      if (k == key_yes) {  // IF VR(100)=13 THEN GOTO setsp
        lab::line t;
        t.cursor(20).add("SPEED:").fixed(vrs.get(speed_vr), 6, 2).add("        ");  // setsp: PRINT #11,"SPEED:";VR(1)[2];
        print(keypad, t);
        go(step::speed);
      } else if (k == key_up && vrs.get(feed_length_vr) < 1000000 * one) {
        vrs.set(feed_length_vr, vrs.get(feed_length_vr) + tenth);
        show_feed_length();
      } else if (k == key_down && vrs.get(feed_length_vr) > tenth) {
        vrs.set(feed_length_vr, vrs.get(feed_length_vr) - tenth);
        show_feed_length();
      }
      return;
    case step::speed:
      if (k == key_yes) {  // initnet: SEND(10,1,0,VR(0)); SEND(10,1,1,VR(1))
        send(axes[0], feed_length_vr, vrs.get(feed_length_vr));
        send(axes[0], speed_vr, vrs.get(speed_vr));
        lab::line t;
        t.add("\x0c\x0e").add("PRESS START TO RUN\r\n");  // start: PRINT #11,CHR(12);CHR(14);"PRESS START TO RUN"
        print(keypad, t);
        go(step::press_start);
      } else if (k == key_up && vrs.get(speed_vr) < 100 * one) {
        vrs.set(speed_vr, vrs.get(speed_vr) + hundredth);
        show_speed();
      } else if (k == key_down && vrs.get(speed_vr) > hundredth) {
        vrs.set(speed_vr, vrs.get(speed_vr) - hundredth);
        show_speed();
      }
      return;
    case step::press_start:
      if (k == key_start) {  // readkey: IF VR(100)<>20 THEN GOTO readkey; PRINT #10,"G";
        vrs.set(ready_vr, 0);
        lab::line t;
        print(axes[0], t.add("G"));
        go(step::wait_running);
      }
      return;
    case step::running:
      if (k == key_stop) menu();
      return;
    default:
      return;
  }
}

// The settings to the host Motion Coordinator, when they change.
void publish() {
  const std::int64_t values[3] = {vrs.get(feed_length_vr), vrs.get(speed_vr),
                                  static_cast<std::int64_t>(now) * one};
  for (std::uint16_t i = 0; i < 3; ++i) {
    if (values[i] == published[i]) continue;
    published[i] = values[i];
    send(host, static_cast<std::uint16_t>(host_vr + i), values[i]);
  }
}

// ---- VR requests to the axis boards ----

struct axis_poll {
  std::uint32_t sequence = 0;  // the request now open (or the last)
  bool open = false;
  std::uint32_t sent_at = 0;
  std::uint32_t sent = 0;
  std::uint32_t answered = 0;
  std::uint32_t wrong = 0;
  std::uint32_t late = 0;
  std::uint32_t lost = 0;
  std::uint32_t lost_log[8] = {};  // the sequence numbers of the first losses
};

axis_poll polls[max_axes];
std::uint32_t poll_period_ticks = 0;
std::uint32_t poll_last = 0;
constexpr std::uint32_t poll_timeout_ticks = 30;  // 300 ms: the request or its answer was lost (or is late)

std::uint16_t poll_vr(unsigned axis, std::uint32_t sequence) {
  return static_cast<std::uint16_t>(poll_base_vr + 100 * axis + sequence % 100);
}

// An answer that came after its request's timeout: the request was counted lost, and was only late.
void late_answer(axis_poll& p, std::int64_t value) {
  ++p.late;
  if (p.lost == 0 || value <= 0 || value % one != 0) return;
  const auto sequence = static_cast<std::uint32_t>((value / one - 1) / 2);
  const std::uint32_t logged = p.lost < 8 ? p.lost : 8;
  for (std::uint32_t i = 0; i < logged; ++i) {
    if (p.lost_log[i] != sequence) continue;
    for (std::uint32_t j = i; j + 1 < logged; ++j) p.lost_log[j] = p.lost_log[j + 1];
    --p.lost;
    return;
  }
  if (p.lost > 8) --p.lost;  // lost after the log was full: it was one of those
}

void take_answers() {
  lab::vr_write w{};
  while (vrs.take(w)) {
    if (w.vr < poll_base_vr) continue;
    const unsigned axis = (w.vr - poll_base_vr) / 100u;
    axis_poll& p = polls[axis];
    const std::int64_t expected = (2 * static_cast<std::int64_t>(p.sequence) + 1) * one;
    if (p.open && w.vr == poll_vr(axis, p.sequence) && w.value == expected) {
      ++p.answered;
      p.open = false;
    } else if (p.open && w.vr == poll_vr(axis, p.sequence)) {
      ++p.wrong;
    } else {
      late_answer(p, w.value);
    }
  }
}

void poll_axes() {
  const std::uint32_t t = ring_link.ticks();
  for (unsigned a = 0; a < axis_count; ++a) {
    axis_poll& p = polls[a];
    if (p.open && t - p.sent_at > poll_timeout_ticks) {
      if (p.lost < 8) p.lost_log[p.lost] = p.sequence;
      ++p.lost;
      p.open = false;
    }
  }
  if (poll_period_ticks == 0 || t - poll_last < poll_period_ticks) return;
  poll_last = t;
  for (unsigned a = 0; a < axis_count; ++a) {
    axis_poll& p = polls[a];
    if (p.open) continue;
    ++p.sequence;
    p.open = true;
    p.sent_at = t;
    ++p.sent;
    send(axes[a], poll_vr(a, p.sequence), static_cast<std::int64_t>(p.sequence) * one);
  }
}

// ---- the debug console ----

void report() {
  lab::line t;
  t.add("lab role=master").field("step", static_cast<std::uint32_t>(now)).field("keys", keys_read);
  t.field("ready_retries", ready_retries);
  t.add(" feed_length=").fixed(vrs.get(feed_length_vr), 0, 4).add(" speed=").fixed(vrs.get(speed_vr), 0, 4);
  t.add(" vr200=").fixed(vrs.get(ready_vr), 0, 4).field("log_overflows", vrs.log_overflows());
  lab::node_fields(t, node, ring_link);
  for (unsigned a = 0; a < axis_count; ++a) {
    const axis_poll& p = polls[a];
    t.add(" poll").number(a + 1).add("=").number(p.sent).add('/').number(p.answered).add('/').number(p.wrong);
    t.add('/').number(p.late).add('/').number(p.lost);
    if (p.lost != 0) {
      t.add(" lost").number(a + 1).add("=");
      for (std::uint32_t i = 0; i < p.lost && i < 8; ++i) t.add(i == 0 ? "" : ",").number(p.lost_log[i]);
    }
  }
  lab::console::answer(t);
}

void serve_console() {
  char command[32];
  if (!console.take(command)) return;
  if (command[0] == 'n') node.clear_netstat();
  if (command[0] == 'p') {
    std::uint32_t ms = 0;
    for (const char* p = command + 1; *p != '\0'; ++p) {
      if (*p >= '0' && *p <= '9') ms = ms * 10 + static_cast<std::uint32_t>(*p - '0');
    }
    poll_period_ticks = ms == 0 ? 0 : (ms + lab::ms_per_tick - 1) / lab::ms_per_tick;
  }
  report();
}

}  // namespace

int main() {
  settings.load();
  keypad = settings.number("keypad", 0);
  offset = settings.number("offset", 10);
  host = settings.number("host", 0);
  start_ticks = static_cast<std::uint32_t>(settings.number("start", 0)) / lab::ms_per_tick;
  for (unsigned i = 0; i < max_axes; ++i) {
    axes[i] = settings.list_item("axes", i);
    if (axes[i] != 0) axis_count = i + 1;
  }
  console.start();
  ring_link.start(static_cast<unsigned>(settings.number("idle", 3)));
  for (;;) {
    serve_console();
    take_answers();
    program_step();
    poll_axes();
    publish();
    lab::sleep();
  }
}
