// The README's ring-node example: a Motion Coordinator and a keypad on a simulated two-node ring.
#include <trionet/ring.hpp>

#include <cstdio>

int main() {
  trionet::vr_table<256> vr;                   // VR(), written by the network through its write policy
  trionet::ring::motion_coordinator<> mc(vr);  // receive buffer 256, forward buffer 16, transmit queue 32
  trionet::ring::keypad<> keypad;              // local mode until its keypad offset arrives

  trionet::ring::simulator<> ring;  // deterministic: one byte per link per byte-time
  (void)ring.add(mc);
  (void)ring.add(keypad);
  (void)mc.send_keypad_offset(10, 10);  // SEND(10,2,10): keys go to the next node, the MC
  ring.run(10);
  (void)keypad.press(trionet::ring::key::up);
  ring.run(10);
  if (mc.key(3)) {  // IF KEY#3 THEN GET #3,k
    const auto k = mc.get(3);
    std::printf("GET #3 -> %u (the up key through DEFKEY)\n", k.value);
    return k.value == 10 ? 0 : 1;
  }
  std::printf("no key arrived\n");
  return 1;
}
