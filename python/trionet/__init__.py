"""trionet: the Trio Motion Coordinator fibre-optic ring, Trio's CAN VR exchange (TN20-17) and the GE Genius
bus, from Python.

The package is the C++ library (include/trionet/ and the host library of the `trionet` tool) bound with
pybind11:

- :mod:`trionet.ring`: encoders, a streaming decoder whose events carry the fields of `trionet ring decode`,
  Motion Coordinator and keypad nodes, the simulated ring, and a node on a serial port;
- :mod:`trionet.basic`: a ring of BASIC programs and keypads, run as `trionet ring simulate` runs it;
- :mod:`trionet.can`: the VR codec to and from python-can messages and a VR-exchange node on any python-can bus;
- :mod:`trionet.genius`: Genius characters, CRC-6, transmissions, bus-access timing and scan time;
- :mod:`trionet.learn`: the CRC and field layout of a network, learned from captured frames;
- :class:`trionet.Profile`: every configurable wire parameter in one JSON file (docs/profile.md).

Misuse of an API (an argument out of range) raises a :class:`StatusError` (a ValueError) whose ``status``
says why, as the C++ status enum spells it; bad data from a wire or a file is never an exception: it comes
back classified (an event, a status) and counted, as in the C++ library. docs/python.md has the overview.
"""

from ._errors import StatusError, TrionetError
from ._profile import Profile, ProfileError
from . import basic, can, genius, learn, ring

__version__ = "0.1.0"

__all__ = ["Profile", "ProfileError", "StatusError", "TrionetError", "basic", "can", "genius", "learn", "ring",
           "__version__"]
