// The Trio Motion Coordinator fibre-optic ring: everything in include/trionet/ring/, and the Q32.32 values
// that direct variable transfers carry (trionet/q32.hpp).
#pragma once

#include "trionet/q32.hpp"
#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decode_result.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/encode.hpp"
#include "trionet/ring/keypad.hpp"
#include "trionet/ring/keypad_codes.hpp"
#include "trionet/ring/keypad_display.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/motion_coordinator.hpp"
#include "trionet/ring/node.hpp"
#include "trionet/ring/simulator.hpp"
#include "trionet/ring/variable_layout.hpp"
