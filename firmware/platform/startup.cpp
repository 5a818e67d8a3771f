// Reset handler and vector table for every firmware image (Cortex-M0+, M3, M4).
//
// No vendor SDK and no C runtime start files (-nostartfiles): the reset handler copies .data from flash,
// zeroes .bss, enables the FPU where there is one, runs static constructors and calls main(). Handlers are
// weak aliases of Default_Handler; a program overrides one by defining a function of the same name.
#include <cstddef>
#include <cstdint>

#include "board.hpp"

extern "C" {
// From sections.ld.
extern std::uint32_t __data_load_start[];
extern std::uint32_t __data_start[];
extern std::uint32_t __data_end[];
extern std::uint32_t __bss_start[];
extern std::uint32_t __bss_end[];
extern std::uint32_t __stack_top[];
extern void (*__init_array_start[])();
extern void (*__init_array_end[])();

// main() itself may not be called from C++; this is the same symbol under another name.
int application_main() __asm__("main");

[[noreturn]] void Reset_Handler();
void Default_Handler();

#define TRIONET_WEAK_HANDLER(name) void name() __attribute__((weak, alias("Default_Handler")))
TRIONET_WEAK_HANDLER(NMI_Handler);
TRIONET_WEAK_HANDLER(HardFault_Handler);
TRIONET_WEAK_HANDLER(MemManage_Handler);
TRIONET_WEAK_HANDLER(BusFault_Handler);
TRIONET_WEAK_HANDLER(UsageFault_Handler);
TRIONET_WEAK_HANDLER(SVC_Handler);
TRIONET_WEAK_HANDLER(DebugMon_Handler);
TRIONET_WEAK_HANDLER(PendSV_Handler);
TRIONET_WEAK_HANDLER(SysTick_Handler);
TRIONET_WEAK_HANDLER(UART0_IRQHandler);
TRIONET_WEAK_HANDLER(UART1_IRQHandler);
TRIONET_WEAK_HANDLER(CAN0_RX0_IRQHandler);
TRIONET_WEAK_HANDLER(TIMER0A_IRQHandler);
#undef TRIONET_WEAK_HANDLER

// A pure virtual call is a bug; stop here rather than pull in libsupc++'s version, which drags in
// std::terminate and abort. (vr_store, the VR port, is an abstract class.)
[[noreturn]] void __cxa_pure_virtual() {
  for (;;) __asm__ volatile("bkpt 0");
}
}

namespace {

using handler = void (*)();

constexpr std::size_t irq_count = 32;

struct vector_table {
  std::uint32_t* initial_stack_pointer;
  handler exceptions[15];  // Reset .. SysTick (exception numbers 1..15)
  handler irqs[irq_count];
};

constexpr vector_table make_vector_table() noexcept {
  vector_table table{__stack_top,
                     {Reset_Handler, NMI_Handler, HardFault_Handler, MemManage_Handler, BusFault_Handler,
                      UsageFault_Handler, nullptr, nullptr, nullptr, nullptr, SVC_Handler, DebugMon_Handler,
                      nullptr, PendSV_Handler, SysTick_Handler},
                     {}};
  for (handler& irq : table.irqs) irq = Default_Handler;
  table.irqs[board::uart0::irq] = UART0_IRQHandler;
  table.irqs[board::uart0::irq + 1] = UART1_IRQHandler;  // the LM3S6965's UART1 (the lab's debug console)
  table.irqs[board::can0::rx0_irq] = CAN0_RX0_IRQHandler;
  table.irqs[19] = TIMER0A_IRQHandler;  // the LM3S6965's general-purpose timer 0A (the Genius test's timer)
  return table;
}

// Placed first in flash by sections.ld; constexpr so that it is built by the compiler, not at run time.
__attribute__((section(".vectors"), used)) constexpr vector_table vectors = make_vector_table();

}  // namespace

extern "C" void Default_Handler() {
  for (;;) {
  }
}

extern "C" void Reset_Handler() {
  const std::uint32_t* from = __data_load_start;
  for (std::uint32_t* to = __data_start; to < __data_end;) *to++ = *from++;
  for (std::uint32_t* to = __bss_start; to < __bss_end;) *to++ = 0;
#if defined(__ARM_FP)
  board::scb::enable_fpu();
#endif
  for (void (**constructor)() = __init_array_start; constructor < __init_array_end; ++constructor) (*constructor)();
  static_cast<void>(application_main());
  for (;;) board::wait_for_interrupt();
}
