// trionet CAN: the TN20-17 VR exchange over CANbus (PROTOCOL.md section 2), in one include.
//
//   can/identifiers.hpp  node, base identifier, receive and transmit channels, both ways
//   can/vr_codec.hpp     the 8-byte VR message: sign, integer part, fraction; rounding
//   can/frame.hpp        a classic CAN frame
//   can/port.hpp         the transmit interface a CAN driver implements
//   can/node.hpp         one controller of the exchange: send VRs, receive frames into VR()
//   can/bus_model.hpp    several controllers on one simulated bus: arbitration, frame times, latency
//
// No heap, no exceptions, no RTTI, no iostream, no clock. Host adapters (candump text, Linux SocketCAN) live
// in src/ of the repository; see docs/can.md.
#pragma once

#include "can/bus_model.hpp"
#include "can/frame.hpp"
#include "can/identifiers.hpp"
#include "can/node.hpp"
#include "can/port.hpp"
#include "can/vr_codec.hpp"
