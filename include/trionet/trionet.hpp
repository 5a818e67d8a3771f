// trionet: the whole library. Include the part you need instead to keep builds small.
#pragma once

#include "trionet/ring.hpp"
#include "trionet/span.hpp"
#include "trionet/vr.hpp"
