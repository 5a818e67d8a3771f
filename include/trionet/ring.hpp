// The Trio Motion Coordinator fibre-optic ring: everything in include/trionet/ring/.
#pragma once

#include "trionet/ring/bytes.hpp"
#include "trionet/ring/crc.hpp"
#include "trionet/ring/decoder.hpp"
#include "trionet/ring/encode.hpp"
#include "trionet/ring/message.hpp"
#include "trionet/ring/q32.hpp"
