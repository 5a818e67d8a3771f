// The lab's axis board: the two-axis Motion Coordinator of the Trio manual's Example 2, which also answers
// VR requests. It waits for "I" from the master, initialises and answers SEND(master,1,200,99); it waits for
// "G", takes the speed the master sent into VR(1) and answers SEND(master,1,200,999). Any VR that the master
// or the host writes into this board's request VRs is answered at once with 2 x value + 1 in the same VR of
// the sender.
//
// Settings (semihosting command line, docs/firmware.md):
//   master=N   the master's BASIC address from this board
//   host=H     the host Motion Coordinator's BASIC address (0: none)
//   index=K    this board's number among the axis boards, 1.. (its request VRs: below)
//   idle=T     ticks of 10 ms without a byte, with a message open, that make the idle line (default 3)
//
// VRs this board owns (its write policy refuses every other, docs/protocol.md 1.6): VR(0) and VR(1), the
// feed length and speed from the master; VR(1000 + 100 (K - 1) + j) and VR(2000 + 100 (K - 1) + j),
// j = 0..99, the master's and the host's requests.
//
// Debug console (UART1): "c" answers the counters, "n" clears NETSTAT. One line back: "lab role=axis ...".
#include <cstddef>
#include <cstdint>

#include "lab_board.hpp"

namespace {

namespace ring = trionet::ring;

constexpr std::uint16_t feed_length_vr = 0;
constexpr std::uint16_t speed_vr = 1;
constexpr std::uint16_t ready_vr = 200;
constexpr std::uint16_t master_requests = 1000;
constexpr std::uint16_t host_requests = 2000;
constexpr std::int64_t one = std::int64_t{1} << 32;

unsigned index_of_board = 1;  // K

std::uint16_t first_request(std::uint16_t base) { return static_cast<std::uint16_t>(base + 100 * (index_of_board - 1)); }

bool owns(std::uint16_t vr) noexcept {
  const auto in = [vr](std::uint16_t base) { return vr >= first_request(base) && vr < first_request(base) + 100; };
  return vr == feed_length_vr || vr == speed_vr || in(master_requests) || in(host_requests);
}

lab::logged_vrs<host_requests + 500> vrs(owns);
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

int master = 0;
int host = 0;
std::uint32_t characters = 0;
std::uint32_t initialised = 0;
std::uint32_t started = 0;
std::uint32_t answered_master = 0;
std::uint32_t answered_host = 0;
std::int64_t speed = 0;  // SPEED=VR(1)

// SEND(n,1,vr,value), waiting for room as BASIC's does (n = 0: no such node).
void send(int n, std::uint16_t vr, std::int64_t value) {
  if (n != 0) static_cast<void>(ring_link.send(n, vr, value));
}

void read_commands() {
  while (node.key(4)) {  // IF NOT(KEY#4) THEN GOTO readinit
    const ring::get_result c = node.get(4);  // GET #4,VR(100)
    ++characters;
    if (c.value == 'I') {  // IF VR(100)<>73 THEN GOTO readinit; GOSUB initax
      ++initialised;
      send(master, ready_vr, 99 * one);  // SEND(11,1,200,99)
    } else if (c.value == 'G') {  // IF VR(100)<>71 THEN GOTO readsp
      speed = vrs.get(speed_vr);  // SPEED=VR(1)
      ++started;
      send(master, ready_vr, 999 * one);  // SEND(11,1,200,999)
    }
  }
}

void answer_requests() {
  lab::vr_write w{};
  while (vrs.take(w)) {
    const std::int64_t answer = 2 * w.value + one;
    if (w.vr >= first_request(host_requests)) {
      send(host, w.vr, answer);
      ++answered_host;
    } else if (w.vr >= first_request(master_requests)) {
      send(master, w.vr, answer);
      ++answered_master;
    }
  }
}

void serve_console() {
  char command[32];
  if (!console.take(command)) return;
  if (command[0] == 'n') node.clear_netstat();
  lab::line t;
  t.add("lab role=axis").field("index", index_of_board).field("characters", characters);
  t.field("initialised", initialised).field("started", started);
  t.field("answered_master", answered_master).field("answered_host", answered_host);
  t.add(" feed_length=").fixed(vrs.get(feed_length_vr), 0, 4).add(" speed=").fixed(speed, 0, 4);
  t.field("log_overflows", vrs.log_overflows());
  lab::node_fields(t, node, ring_link);
  lab::console::answer(t);
}

}  // namespace

int main() {
  settings.load();
  master = settings.number("master", 0);
  host = settings.number("host", 0);
  index_of_board = static_cast<unsigned>(settings.number("index", 1));
  if (index_of_board < 1 || index_of_board > 4) index_of_board = 1;
  console.start();
  ring_link.start(static_cast<unsigned>(settings.number("idle", 3)));
  for (;;) {
    serve_console();
    read_commands();
    answer_requests();
    lab::sleep();
  }
}
