// Not firmware: a deliberately bad image that scripts/firmware-build links to prove that
// tools/check-symbols rejects heap and exception symbols (it must name them and fail).
#include <cstdlib>
#include <new>

void* volatile kept;  // stops the compiler from eliding the allocations

extern "C" void Reset_Handler() {
  kept = std::malloc(16);
  std::free(kept);
  kept = new int(7);
  delete static_cast<int*>(kept);
  for (;;) {
  }
}
