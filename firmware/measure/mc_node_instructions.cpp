// The firmware MC program's UART interrupt (programs/mc_node_link.hpp) on the emulated Cortex-M3, with a
// quiet main loop, for scripts/firmware-instructions: the main loop only reads the characters that arrive
// (GET#4) until a keypad mode message to this node ends the run, then reports the node's counters through
// semihosting. The script counts the Thumb instructions that the interrupt executes per byte.
#include <cstdint>

#include "../programs/mc_node_link.hpp"
#include "board.hpp"
#include "semihosting.hpp"

int main() {
  board::uart0::start();
  std::uint32_t characters = 0;
  for (;;) {  // (no wfi: under qemu's instruction trace a core asleep may miss the serial input)
    while (node.key(4)) {
      static_cast<void>(node.get(4));
      ++characters;
    }
    if (node.counters().keypad_messages_ignored == 0) continue;  // the end of the run
    // Nothing arrives after the end: what is read now is final (counters() reads one counter at a time).
    while (node.key(4)) {
      static_cast<void>(node.get(4));
      ++characters;
    }
    const ring::motion_coordinator_counters c = node.counters();
    const ring::link_counters links = node.forwarding_counters();
    semihosting::report("forwarded ", links.messages_forwarded);
    semihosting::report("character_messages ", c.character_messages);
    semihosting::report("characters_read ", characters);
    semihosting::report("variables_written ", c.variables_written);
    semihosting::report("frame_errors ", c.frame_errors);
    semihosting::report("crc_errors ", c.crc_errors);
    semihosting::report("receive_overflows ", c.receive_overflows);
    semihosting::report("forwards_failed ", links.forwards_failed());
    semihosting::exit(0);
  }
}
