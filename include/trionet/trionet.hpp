// trionet: the whole library (the ring, CAN and Genius parts). Include the part you need instead to keep
// builds small.
#pragma once

#include "trionet/can.hpp"
#include "trionet/genius.hpp"
#include "trionet/q32.hpp"
#include "trionet/ring.hpp"
#include "trionet/span.hpp"
#include "trionet/vr.hpp"
