// The registers the firmware images touch, as plain volatile addresses (no vendor SDK).
//
// A generic Cortex-M board:
//   UART0 is an Arm PL011 at 0x4000C000 on IRQ 5 (as on the TI LM3S6965, which qemu emulates);
//   CAN0 is an ST bxCAN at 0x40006400, receive FIFO 0 on IRQ 20 (as on the STM32F103);
//   the Genius device's 9-bit USART is an STM32L0/G0-style USART at 0x40004400, on the UART0 vector (that
//   image has no PL011), and its block's inputs and outputs are GPIO ports A and B at 0x50000000 (IDR, ODR).
// Only what the programs use is here. Everything is inline and ISR-safe.
#pragma once

#include <cstdint>

namespace board {

inline volatile std::uint32_t& reg(std::uintptr_t address) noexcept {
  return *reinterpret_cast<volatile std::uint32_t*>(address);
}

inline void wait_for_interrupt() noexcept { __asm__ volatile("wfi"); }
inline void disable_interrupts() noexcept { __asm__ volatile("cpsid i" ::: "memory"); }
inline void enable_interrupts() noexcept { __asm__ volatile("cpsie i" ::: "memory"); }

namespace nvic {
inline void enable(unsigned irq) noexcept { reg(0xE000E100u + 4u * (irq / 32u)) = 1u << (irq % 32u); }
}  // namespace nvic

namespace scb {
/// CP10 and CP11 full access (Cortex-M4F): required before the first floating-point instruction.
inline void enable_fpu() noexcept {
  reg(0xE000ED88u) |= 0xFu << 20;
  __asm__ volatile("dsb\n\tisb" ::: "memory");
}
}  // namespace scb

namespace systick {
inline void start(std::uint32_t reload) noexcept {
  reg(0xE000E014u) = reload;  // LOAD
  reg(0xE000E018u) = 0;       // VAL
  reg(0xE000E010u) = 7;       // CTRL: processor clock, interrupt, enable
}
}  // namespace systick

/// PL011 UART.
namespace uart0 {
constexpr std::uintptr_t base = 0x4000C000u;
constexpr unsigned irq = 5;
constexpr std::uint32_t flag_rx_empty = 1u << 4;  // FR.RXFE
constexpr std::uint32_t flag_tx_full = 1u << 5;   // FR.TXFF

inline volatile std::uint32_t& data() noexcept { return reg(base + 0x00u); }   // DR
inline volatile std::uint32_t& flags() noexcept { return reg(base + 0x18u); }  // FR

inline bool rx_ready() noexcept { return (flags() & flag_rx_empty) == 0; }
inline std::uint8_t read() noexcept { return static_cast<std::uint8_t>(data() & 0xFFu); }
inline bool tx_ready() noexcept { return (flags() & flag_tx_full) == 0; }
inline void write(std::uint8_t byte) noexcept { data() = byte; }

constexpr std::uint32_t interrupt_rx = (1u << 4) | (1u << 6);  // IMSC.RXIM, IMSC.RTIM
constexpr std::uint32_t interrupt_tx = 1u << 5;                 // IMSC.TXIM

inline volatile std::uint32_t& interrupt_mask() noexcept { return reg(base + 0x38u); }  // IMSC

/// Transmit interrupt on or off. Safe without interrupt masking as the programs use it: the main loop only
/// switches it on, the UART ISR only off; a read-modify-write of one that the other interrupts leaves the
/// interrupt on at worst, and the ISR then finds nothing to send and switches it off.
inline void enable_tx_interrupt(bool on) noexcept {
  if (on) {
    interrupt_mask() |= interrupt_tx;
  } else {
    interrupt_mask() &= ~interrupt_tx;
  }
}

/// 8N1, receive and receive-timeout interrupts on.
inline void start() noexcept {
  reg(base + 0x2Cu) = 0x60u;                 // LCRH: 8 data bits, FIFOs off
  interrupt_mask() = interrupt_rx;
  reg(base + 0x30u) = 0x301u;                // CR: UARTEN, TXE, RXE
  nvic::enable(irq);
}
}  // namespace uart0

/// A 9-bit USART for the Genius bus, in the register layout of the STM32L0/G0 USARTs (CR1, CR3, BRR, ISR,
/// ICR, RDR, TDR), on the UART0 vector: 9 data bits (M0), the receive interrupt, and the wake-up flag set on
/// a start bit (WUS = 10, WUFIE). On a part that raises that flag only in Stop mode, a falling-edge
/// interrupt on RX, enabled between characters, does the same.
namespace usart9 {
constexpr std::uintptr_t base = 0x40004400u;
constexpr unsigned irq = uart0::irq;
constexpr std::uint32_t isr_framing_error = 1u << 1;  // ISR.FE
constexpr std::uint32_t isr_rx_not_empty = 1u << 5;   // ISR.RXNE
constexpr std::uint32_t isr_start_bit = 1u << 20;     // ISR.WUF (WUS = start bit)

inline volatile std::uint32_t& isr() noexcept { return reg(base + 0x1Cu); }
inline volatile std::uint32_t& icr() noexcept { return reg(base + 0x20u); }
inline volatile std::uint32_t& rdr() noexcept { return reg(base + 0x24u); }
inline volatile std::uint32_t& tdr() noexcept { return reg(base + 0x28u); }

inline void start(std::uint32_t clock_hz, std::uint32_t baud) noexcept {
  reg(base + 0x0Cu) = clock_hz / baud;                         // BRR
  reg(base + 0x08u) = (2u << 20) | (1u << 22);                 // CR3: WUS = start bit, WUFIE
  reg(base + 0x00u) = (1u << 12) | (1u << 5) | (1u << 3) | (1u << 2) | (1u << 1) | 1u;  // CR1: M0 (9 bits),
                                                               // RXNEIE, TE, RE, UESM, UE
  nvic::enable(irq);
}
}  // namespace usart9

/// SysTick as a one-shot timer: it counts `cycles` and interrupts once if the handler stops it.
namespace systick {
inline void start_once(std::uint32_t cycles) noexcept {
  reg(0xE000E010u) = 0;           // CTRL: stopped
  reg(0xE000E014u) = cycles - 1;  // LOAD
  reg(0xE000E018u) = 0;           // VAL
  reg(0xE000E010u) = 7;           // CTRL: processor clock, interrupt, enable
}
/// Stops it, and withdraws its interrupt if it is already pending (ICSR.PENDSTCLR): a timer cancelled from
/// another handler of the same priority must not still interrupt.
inline void stop() noexcept {
  reg(0xE000E010u) = 0;
  reg(0xE000ED04u) = 1u << 25;
}
}  // namespace systick

/// General-purpose inputs and outputs (STM32L0-style ports A and B): a block's 32 inputs and 32 outputs.
namespace gpio {
inline std::uint32_t inputs() noexcept { return reg(0x50000010u); }           // IDR
inline void set_outputs(std::uint32_t value) noexcept { reg(0x50000414u) = value; }  // ODR
}  // namespace gpio

/// bxCAN: receive FIFO 0 and transmit mailbox 0.
namespace can0 {
constexpr std::uintptr_t base = 0x40006400u;
constexpr unsigned rx0_irq = 20;

inline volatile std::uint32_t& tsr() noexcept { return reg(base + 0x008u); }   // transmit status
inline volatile std::uint32_t& rf0r() noexcept { return reg(base + 0x00Cu); }  // receive FIFO 0 status
inline volatile std::uint32_t& ier() noexcept { return reg(base + 0x014u); }   // interrupt enable
inline volatile std::uint32_t& ti0r() noexcept { return reg(base + 0x180u); }  // TX mailbox 0 identifier
inline volatile std::uint32_t& tdt0r() noexcept { return reg(base + 0x184u); }
inline volatile std::uint32_t& tdl0r() noexcept { return reg(base + 0x188u); }
inline volatile std::uint32_t& tdh0r() noexcept { return reg(base + 0x18Cu); }
inline volatile std::uint32_t& ri0r() noexcept { return reg(base + 0x1B0u); }  // RX FIFO 0 identifier
inline volatile std::uint32_t& rdt0r() noexcept { return reg(base + 0x1B4u); }
inline volatile std::uint32_t& rdl0r() noexcept { return reg(base + 0x1B8u); }
inline volatile std::uint32_t& rdh0r() noexcept { return reg(base + 0x1BCu); }

/// A classic CAN frame as the registers hold it, in parts: `identifier` follows the SocketCAN convention (the
/// 11- or 29-bit identifier, bit 31 set for an extended frame, bit 30 for a remote frame), `length` is the
/// DLC, `data` the 8 data bytes. Parts rather than a struct, so that a program reads into and writes from its
/// own frame type without a copy.
constexpr std::uint32_t extended_flag = 1u << 31;
constexpr std::uint32_t remote_flag = 1u << 30;

inline bool rx_pending() noexcept { return (rf0r() & 0x3u) != 0; }  // FMP0

/// Reads the oldest frame of FIFO 0 and releases it.
inline void read(std::uint32_t& identifier, std::uint8_t& length, std::uint8_t (&data)[8]) noexcept {
  const std::uint32_t rir = ri0r();
  identifier = (rir & 0x4u) != 0 ? extended_flag | (rir >> 3) : rir >> 21;  // IDE: EXID or STID
  if ((rir & 0x2u) != 0) identifier |= remote_flag;                          // RTR
  length = static_cast<std::uint8_t>(rdt0r() & 0xFu);
  const std::uint32_t low = rdl0r();
  const std::uint32_t high = rdh0r();
  for (unsigned i = 0; i < 4; ++i) {
    data[i] = static_cast<std::uint8_t>(low >> (8u * i));
    data[4 + i] = static_cast<std::uint8_t>(high >> (8u * i));
  }
  rf0r() = 1u << 5;  // RFOM0: release the FIFO output mailbox
}

inline bool tx_free() noexcept { return (tsr() & (1u << 26)) != 0; }  // TME0

/// Puts a standard data frame in transmit mailbox 0 and requests its transmission.
inline void write(std::uint32_t identifier, std::uint8_t length, const std::uint8_t (&data)[8]) noexcept {
  std::uint32_t low = 0;
  std::uint32_t high = 0;
  for (unsigned i = 0; i < 4; ++i) {
    low |= static_cast<std::uint32_t>(data[i]) << (8u * i);
    high |= static_cast<std::uint32_t>(data[4 + i]) << (8u * i);
  }
  tdt0r() = length;
  tdl0r() = low;
  tdh0r() = high;
  ti0r() = ((identifier & 0x7FFu) << 21) | 1u;  // STID (standard frames only), TXRQ
}

inline void start() noexcept {
  ier() = 1u << 1;  // FMPIE0: FIFO 0 message pending
  nvic::enable(rx0_irq);
}
}  // namespace can0

/// The keypad's key matrix, scanned by hardware: bit k of the latched state is 1 while key k is down
/// (k in trionet::ring::key order).
namespace keys {
inline std::uint32_t pressed() noexcept { return reg(0x40005000u); }
}  // namespace keys

}  // namespace board
