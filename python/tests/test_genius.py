"""trionet.genius against `trionet genius encode|timing|scan-time` and the manual's figures."""

import json
import random

import pytest

import trionet
from trionet import genius


def cli_characters(text):
    """`genius encode` output ("c:XX" control, "XX" data) as characters."""
    return [genius.Character(int(w[2:], 16), True) if w.startswith("c:") else genius.Character(int(w, 16), False)
            for w in text.split()]


@pytest.mark.parametrize("args,transmission", [
    (["--from", "3", "--to", "7", "1122", "block:9:334455", "66"],
     genius.Transmission(3, (genius.Segment(b"\x11\x22"), genius.Segment(b"\x33\x44\x55", True, 9),
                             genius.Segment(b"\x66")), destination=7)),
    (["--from", "31", "--broadcast", "00"], genius.Transmission(31, (genius.Segment(b"\x00"),))),
    (["--from", "0", "--to", "0"], genius.Transmission(0, (), destination=0)),
])
def test_transmissions_are_the_characters_the_tool_encodes(run_cli, args, transmission):
    assert genius.encode_transmission(transmission) == cli_characters(run_cli(["genius", "encode"] + args))
    words = run_cli(["genius", "encode", "--words"] + args).split()
    assert genius.encode_words(transmission) == [int(w[2:], 16) for w in words]


def test_a_transmission_comes_back_from_its_characters():
    rnd = random.Random(5)
    for _ in range(50):
        segments = tuple(genius.Segment(rnd.randbytes(rnd.randint(1, 8)), rnd.random() < 0.5, rnd.randrange(32))
                         for _ in range(rnd.randint(1, 4)))
        segments = tuple(genius.Segment(s.data, s.block, s.destination if s.block else 0) for s in segments)
        t = genius.Transmission(rnd.randrange(32), segments, rnd.choice([None, rnd.randrange(32)]))
        (back,) = genius.decode_transmissions(genius.encode_transmission(t))
        assert (back.sender, back.destination, back.data) == (t.sender, t.destination, t.data)
        assert [s.block for s in back.segments if s.block] == [s.block for s in t.segments if s.block]


def test_wire_errors_are_statuses_and_the_parser_finds_the_next_start():
    t = genius.Transmission(3, (genius.Segment(b"\x01\x02"),), destination=4)
    good = genius.encode_transmission(t)
    bad = list(good)
    bad[-1] = genius.Character(bad[-1].byte ^ 1, True)  # the Stop's CRC
    parser = genius.TransmissionParser()
    statuses = [parser.push(c) for c in bad + [genius.Character(0x55)] + good]
    assert genius.ParseStatus.stop_crc_mismatch in statuses and statuses[-1] is genius.ParseStatus.ok
    assert parser.received.data == b"\x01\x02" and parser.errors == 1
    assert parser.counts()["stop_crc_mismatch"] == 1
    assert parser.push_framing_error() in (genius.ParseStatus.framing_error, genius.ParseStatus.skipped)


def test_characters_and_words():
    word = genius.encode_character(genius.Character(0xA5, True))
    assert genius.decode_character(word).character == genius.Character(0xA5, True)
    assert genius.decode_character(word | 1).status is genius.CharacterStatus.start_bit_not_0
    assert not genius.decode_character(word & ~0x400)
    assert genius.crc6(b"123456789") == 0x06  # CRC-6/G-704's check value


@pytest.mark.parametrize("call,status", [
    (lambda: genius.encode_transmission(genius.Transmission(32, (genius.Segment(b"\x01"),))),
     genius.EncodeStatus.sender_out_of_range),
    (lambda: genius.encode_transmission(genius.Transmission(1, (genius.Segment(b"\x01"),), destination=40)),
     genius.EncodeStatus.destination_out_of_range),
    (lambda: genius.encode_transmission(genius.Transmission(1, ())), genius.EncodeStatus.empty_transmission),
    (lambda: genius.encode_transmission(genius.Transmission(1, (genius.Segment(b"", True, 2),))),
     genius.EncodeStatus.empty_block),
    (lambda: genius.bus_scan_time("38.4", [1] * 17), genius.ScanTimeStatus.too_many_devices),
])
def test_misuse_raises_a_status_error(call, status):
    with pytest.raises(trionet.StatusError) as raised:
        call()
    assert raised.value.status is status


def test_the_manuals_worked_timing_example(run_cli):
    devices = [genius.Device(4, 0), genius.Device(5, 2000), genius.Device(6, 0)]
    timing = genius.BusTiming.default("153.6s")
    timing = genius.BusTiming(timing.rate, timing.bit_time_us, 26.0, timing.propagation_us_per_2000ft,
                              timing.detection_us)
    a = genius.analyse_turns(devices, timing, after=4)
    assert [(t.sba, round(t.start_us, 6)) for t in a.turns] == [(5, 29.0), (6, 52.0)]
    assert [(m.first, m.second, round(m.margin_us, 6), m.too_small) for m in a.margins] == [(5, 6, 20.0, False)]
    cli = json.loads(run_cli(["genius", "timing", "--rate", "153.6s", "--after", "4", "--device", "4@0", "--device",
                              "5@2000", "--device", "6@0", "--skip-us", "26", "--json"]))
    assert [(t["sba"], t["start_us"]) for t in cli["turns"]] == [(t.sba, pytest.approx(t.start_us)) for t in a.turns]
    with pytest.raises(trionet.StatusError):
        genius.analyse_turns(devices, timing, after=9)


def test_a_bus_scan_comes_round(run_cli):
    scan = genius.simulate_scan([genius.Device(s, 100.0 * s, 4) for s in range(1, 6)], "153.6s", after=1)
    assert scan.complete and scan.collisions == 0
    assert [t.sba for t in scan.transmissions] == [2, 3, 4, 5, 1]


def test_scan_time_is_ges_figure_and_the_tools(run_cli):
    cli = json.loads(run_cli(["genius", "scan-time", "--rate", "153.6s", "--device", "4,8,16", "--json"]))
    s = genius.bus_scan_time("153.6s", [4, 8, 16])
    assert s.total_ns == round(cli["sum_ms"] * 1e6) == 4831000 and s.io_bytes == 28 and s.devices == 3
    assert genius.device_scan_time_ns(genius.Rate.baud_38k4, 0) == 2583000
    assert genius.rate_properties(genius.rate_from_name("153.6e"))["max_length_ft"] == 3500
    with pytest.raises(ValueError):
        genius.rate_from_name("9600")


def test_what_the_decoder_would_reject_is_not_encoded_as_the_tool_refuses_it(run_cli):
    # 257 data bytes, or 17 segments: `genius encode` exits 2 ("the decoder would report overflow").
    too_long = genius.Transmission(1, (genius.Segment(bytes(257)),))
    with pytest.raises(trionet.StatusError) as raised:
        genius.encode_transmission(too_long)
    assert raised.value.status is genius.ParseStatus.overflow
    run_cli(["genius", "encode", "--from", "1", "--broadcast", "00" * 257], status=2)
    too_many = genius.Transmission(1, tuple(genius.Segment(b"a", True, 2) for _ in range(17)))
    with pytest.raises(trionet.StatusError):
        genius.encode_words(too_many)
    run_cli(["genius", "encode", "--from", "1", "--broadcast"] + ["block:2:61"] * 17, status=2)
    # At the limits, encoded, the tool's characters, and decoded back.
    for t, args in [(genius.Transmission(1, (genius.Segment(bytes(range(256))),)),
                     ["--broadcast", bytes(range(256)).hex()]),
                    (genius.Transmission(1, tuple(genius.Segment(b"a", True, 2) for _ in range(16))),
                     ["--broadcast"] + ["block:2:61"] * 16)]:
        characters = genius.encode_transmission(t)
        assert characters == cli_characters(run_cli(["genius", "encode", "--from", "1"] + args))
        assert genius.decode_transmissions(characters) == [t]
