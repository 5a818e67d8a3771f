// trionet CAN: the TN20-17 VR exchange over CANbus (docs/protocol.md section 2), in one include.
//
//   can/identifiers.hpp  node, base identifier, receive and transmit channels, both ways
//   can/vr_codec.hpp     the 8-byte VR message: sign, integer part, fraction; rounding; a frame's VR message
//   can/frame.hpp        a classic CAN frame
//   can/port.hpp         the transmit interface a CAN driver implements
//   can/node.hpp         one controller of the exchange: send VRs, receive frames into VR()
//   can/bus_model.hpp    several controllers on one simulated bus: arbitration, frame times, latency
//
// No heap, no exceptions, no RTTI, no iostream, no clock. Host adapters (candump text, Linux SocketCAN) live
// in src/ of the repository; see docs/can.md.
#pragma once

#include "trionet/can/bus_model.hpp"
#include "trionet/can/frame.hpp"
#include "trionet/can/identifiers.hpp"
#include "trionet/can/node.hpp"
#include "trionet/can/port.hpp"
#include "trionet/can/vr_codec.hpp"
