// Must not compile: a forward buffer of 8 bytes cannot hold what arrives while the node sends a direct
// variable transfer of its own (16 bytes), so forwarded traffic would be lost (docs/liveness.md).
#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/vr.hpp"

int main() {
  trionet::vr_table<16> vr;
  trionet::ring::motion_coordinator<256, 8, 32> mc(vr);
  return static_cast<int>(mc.transmit_free());
}
