// The GE Genius bus part of trionet (docs/protocol.md section 3): the 11-bit character codec and bit-stream
// receiver, the CRC-6 policy, transmissions (encoder and streaming parser), the bus-access timing model and
// GE's scan time. See docs/genius.md.
#pragma once

#include "trionet/genius/bus_access.hpp"
#include "trionet/genius/character.hpp"
#include "trionet/genius/crc6.hpp"
#include "trionet/genius/scan_time.hpp"
#include "trionet/genius/transmission.hpp"
