#!/usr/bin/env python3
"""A CAN test bench for the TN20-17 VR exchange: two controllers on one python-can bus, one sending VRs to
the other, and a check that every VR arrived, in order, with the value sent.

    python3 examples/python/can_bench.py                                  # python-can's virtual bus
    python3 examples/python/can_bench.py --count 100000 --timing          # a longer run, timed
    python3 examples/python/can_bench.py --interface socketcan --channel vcan0

Any python-can interface works (--interface pcan --channel PCAN_USBBUS1, kvaser, vector, ixxat, ...): on a
real bus, run the receiving node on the bench PC and the sender in the controller, or both here with two
channels. Exit status 0 when nothing was lost or wrong, 1 otherwise.
"""

import argparse
import sys
import time

import can

from trionet import TrionetError
from trionet import can as tcan


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0].replace("\n", " "))
    parser.add_argument("--interface", default="virtual", help="python-can interface (default: virtual)")
    parser.add_argument("--channel", default=None, help="channel (default: a fresh virtual channel)")
    parser.add_argument("--count", type=int, default=10000, help="VRs to send (default 10000)")
    parser.add_argument("--nodes", type=int, default=5, help="controllers on the exchange (default 5)")
    parser.add_argument("--sender", type=int, default=1, help="the sending node (default 1)")
    parser.add_argument("--receiver", type=int, default=4, help="the receiving node (default 4)")
    parser.add_argument("--timing", action="store_true", help="also print how long it took")
    args = parser.parse_args()
    if args.count < 1:
        parser.error(f"--count is the number of VRs to send, at least 1, not {args.count}")
    if args.sender == args.receiver:
        parser.error(f"--sender and --receiver are both node {args.sender}: a node does not send to itself")

    channel = args.channel or "bench"  # a virtual channel is private to this process
    with can.Bus(interface=args.interface, channel=channel) as bus_a, \
            can.Bus(interface=args.interface, channel=channel) as bus_b:
        try:
            sender = tcan.VrExchangeNode(bus_a, args.sender, args.nodes)
            receiver = tcan.VrExchangeNode(bus_b, args.receiver, args.nodes)
        except (ValueError, TrionetError) as e:  # a node number or count the exchange does not have
            parser.error(str(e))
        receiver.start()  # its own thread reads the bus

        expected = [(i % 256, (i * 37 % 2000003) / 1000.0 - 1000.0) for i in range(args.count)]
        wrong = 0
        got = 0
        started = time.perf_counter()
        incoming = receiver.received(timeout=10.0)  # a VR missing for 10 s is lost
        for vr, value in expected:
            sender.send(args.receiver, vr, value)
        for (vr, value), received in zip(expected, incoming):
            got += 1
            if (received.sender, received.vr) != (args.sender, vr) or abs(received.value - value) > 5e-5:
                wrong += 1
        elapsed = time.perf_counter() - started
        receiver.stop()

        lost = args.count - got
        counts = receiver.counters()
        print(f"{args.interface} {channel}: node {args.sender} -> node {args.receiver} of {args.nodes}")
        print(f"{args.count} VRs sent, {got} received, {lost} lost, {wrong} wrong")
        print(f"sender: {sender.counters()['sent']} frames sent, {sender.counters()['send_failed']} failed; "
              f"receiver: {counts['written']} written, {counts['foreign']} foreign, "
              f"{counts['bad_dlc'] + counts['bad_sign'] + counts['bad_fraction']} malformed")
        if args.timing:
            print(f"{elapsed:.2f} s, {args.count / elapsed:.0f} VRs/s")
        return 0 if lost == 0 and wrong == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
