// The GE Genius bus part of trionet (PROTOCOL.md section 3): the 11-bit character codec and bit-stream
// receiver, the CRC-6 policy, transmissions (encoder and streaming parser) and the bus-access timing model.
// See docs/genius.md.
#pragma once

#include "genius/bus_access.hpp"
#include "genius/character.hpp"
#include "genius/crc6.hpp"
#include "genius/transmission.hpp"
