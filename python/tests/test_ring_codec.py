"""trionet.ring's encoders and decoder against `trionet ring encode` and `trionet ring decode --raw`."""

import decimal
import json
import random

import pytest

import trionet
from trionet import ring


ENCODE_CASES = [
    ("print", ["--to", "11", "HELLO"], lambda: ring.encode_print(11, "HELLO")),
    ("print", ["--to", "24", "\x0cSPEED:\r\nLENGTH:"], lambda: ring.encode_print(24, "\x0cSPEED:\r\nLENGTH:")),
    ("print", ["--to", "10", "x" * 256], lambda: ring.encode_print(10, b"x" * 256)),
    ("var", ["--to", "10", "--vr", "200", "--value", "99"], lambda: ring.encode_var(10, 200, 99)),
    ("var", ["--to", "12", "--vr", "16383", "--value", "-2.345"], lambda: ring.encode_var(12, 16383, -2.345)),
    ("var", ["--to", "10", "--vr", "0", "--value", "-2147483648"], lambda: ring.encode_var(10, 0, -2147483648)),
    ("var", ["--to", "10", "--vr", "1", "--value", "0.001"], lambda: ring.encode_var(10, 1, 0.001)),
    ("offset", ["--to", "10", "--offset", "11"], lambda: ring.encode_offset(10, 11)),
    ("offset", ["--to", "24", "--offset", "24"], lambda: ring.encode_offset(24, 24)),
    ("mode", ["--to", "10", "--mode", "127"], lambda: ring.encode_mode(10, 127)),
    ("mode", ["--to", "15", "--mode", "0"], lambda: ring.encode_mode(15, 0)),
]


@pytest.mark.parametrize("kind,args,encode", ENCODE_CASES)
def test_encoders_give_the_frames_the_tool_gives(run_cli, kind, args, encode):
    assert encode().hex(" ") == run_cli(["ring", "encode", kind] + args).strip()


def test_a_message_encodes_as_its_encoder_does():
    assert ring.encode(ring.Message.characters(2, "HELLO")) == ring.encode_print(11, "HELLO")
    assert ring.encode(ring.Message.variable(1, 200, 99.0)) == ring.encode_var(10, 200, 99)
    assert ring.encode(ring.Message.keypad_offset(1, 2)) == ring.encode_offset(10, 11)
    assert ring.encode(ring.Message.keypad_mode(1, 127)) == ring.encode_mode(10, 127)


@pytest.mark.parametrize("call,status", [
    (lambda: ring.encode_print(9, "A"), ring.EncodeStatus.hops_out_of_range),
    (lambda: ring.encode_print(25, "A"), ring.EncodeStatus.hops_out_of_range),
    (lambda: ring.encode_print(10, ""), ring.EncodeStatus.empty_text),
    (lambda: ring.encode_print(10, "caf\u00e9"), ring.EncodeStatus.character_out_of_range),
    (lambda: ring.encode_print(10, b"\x80"), ring.EncodeStatus.character_out_of_range),
    (lambda: ring.encode_var(10, 16384, 1), ring.EncodeStatus.vr_out_of_range),
    (lambda: ring.encode_var(10, -1, 1), ring.EncodeStatus.vr_out_of_range),
    (lambda: ring.encode_offset(10, 25), ring.EncodeStatus.hops_out_of_range),
    (lambda: ring.encode_mode(10, 1), ring.EncodeStatus.mode_out_of_range),
    (lambda: ring.encode_mode(10, 1000), ring.EncodeStatus.mode_out_of_range),
    (lambda: ring.encode(ring.Message.characters(16, "A")), ring.EncodeStatus.hops_out_of_range),
    (lambda: ring.encode(ring.Message.characters(0, "A")), ring.EncodeStatus.hops_out_of_range),
    (lambda: ring.encode(ring.Message.keypad_offset(1, 0)), ring.EncodeStatus.offset_out_of_range),
    (lambda: ring.encode(ring.Message.keypad_offset(1, 16)), ring.EncodeStatus.offset_out_of_range),
])
def test_misuse_of_an_encoder_raises_a_status_error_naming_the_reason(call, status):
    with pytest.raises(trionet.StatusError) as raised:
        call()
    assert raised.value.status is status
    assert isinstance(raised.value, ValueError)
    assert status.name in str(raised.value)


@pytest.mark.parametrize("value,status", [(float("nan"), ring.Q32Status.not_a_number),
                                           (2.0**31, ring.Q32Status.out_of_range),
                                           (float("inf"), ring.Q32Status.out_of_range)])
def test_a_value_without_a_q32_form_is_refused(value, status):
    with pytest.raises(trionet.StatusError) as raised:
        ring.encode_var(10, 1, value)
    assert raised.value.status is status


def test_q32_conversions_round_as_send_does():
    assert ring.q32_from_float(99) == 99 << 32
    assert ring.q32_from_float(-0.5) == -(1 << 31)
    assert ring.q32_to_float(ring.q32_from_float(2.345)) == pytest.approx(2.345, abs=2**-32)
    assert ring.hops_from_basic_address(10) == 1 and ring.basic_address_from_hops(15) == 24
    with pytest.raises(ValueError):
        ring.hops_from_basic_address(25)


def cli_events(run_cli, data, profile=None):
    """The tool's events for raw bytes: its "position" is the package's Event.position."""
    args = ["ring", "decode", "--raw"] + (["--profile", profile] if profile else [])
    events = []
    for line in run_cli(args, stdin=data).splitlines():
        pairs = json.loads(line, object_pairs_hook=list)
        assert pairs[1][0] == "position"
        keys = [k for k, _ in pairs]
        assert len(keys) == len(set(keys)), line  # one key once (a keypad offset message has its own "offset")
        events.append(dict(pairs))
    return events


def mixed_stream(seed, size):
    """Frames of every kind, with errors: stray bytes, cut messages, flipped bits."""
    rnd = random.Random(seed)
    frames = [ring.encode_print(11, "HELLO"), ring.encode_var(10, 200, 99), ring.encode_offset(10, 11),
              ring.encode_mode(10, 127), ring.encode_var(24, 7, -2.345),
              ring.encode(ring.Message.characters(1, "x" * 300))]  # longer than a decoder takes
    out = bytearray()
    while len(out) < size:
        frame = bytearray(rnd.choice(frames))
        roll = rnd.random()
        if roll < 0.1:
            frame[rnd.randrange(len(frame))] ^= 1 << rnd.randrange(8)
        elif roll < 0.15:
            frame = frame[: rnd.randrange(len(frame))]
        elif roll < 0.2:
            frame += bytes(rnd.randrange(256) for _ in range(rnd.randrange(1, 6)))
        out += frame
    return bytes(out)


@pytest.mark.parametrize("seed", range(3))
def test_decoder_events_are_the_tools_events(run_cli, seed):
    data = mixed_stream(seed, 20000)
    decoder = ring.Decoder()
    events = [e.to_dict() for e in decoder.feed(data) + decoder.finish()]
    expected = cli_events(run_cli, data)
    assert len(events) > 100
    assert events == expected


def test_decoder_events_on_random_bytes_are_the_tools_events(run_cli):
    data = random.Random(7).randbytes(50000)
    assert [e.to_dict() for e in ring.decode(data)] == cli_events(run_cli, data)


def test_a_stream_fed_in_any_pieces_gives_the_same_events():
    data = mixed_stream(11, 5000)
    whole = [e.to_dict() for e in ring.decode(data)]
    rnd = random.Random(3)
    for _ in range(20):
        decoder = ring.Decoder()
        events, at = [], 0
        while at < len(data):
            n = rnd.choice([1, 2, 3, 7, 16, 100, 4096])
            events += decoder.feed(data[at:at + n])
            at += n
        events += decoder.finish()
        assert [e.to_dict() for e in events] == whole
    assert decoder.position == len(data)


def test_event_fields_read_as_the_tool_prints_them():
    var, text, offset, mode = ring.decode(ring.encode_var(10, 200, 99) + ring.encode_print(11, "HI\r\n")
                                          + ring.encode_offset(10, 11) + ring.encode_mode(10, 127))
    assert (var.event, var.position, var.type, var.hops, var.vr, var.raw, var.value) == \
        ("message", 0, "var", 1, 200, "0x0000006300000000", 99.0)
    assert var.status is ring.DecodeStatus.ok and var.error is None and var.text is None
    assert (text.type, text.hops, text.text, text.position) == ("char", 2, "HI\r\n", 16)
    assert (offset.type, offset.offset, mode.type, mode.mode) == ("offset", 2, "mode", 127)
    assert repr(text) == "Event(event='message', position=16, type='char', hops=2, text='HI\\r\\n')"
    assert var == ring.decode(ring.encode_var(10, 200, 99))[0] and var != text


def test_errors_say_what_and_where():
    stray, stray_eom = ring.decode(bytes.fromhex("01 88"))
    assert (stray.event, stray.reason, stray.error, stray.position) == \
        ("frame_error", "stray_data", ring.FrameError.stray_data, 0)
    assert (stray_eom.reason, stray_eom.position) == ("stray_eom", 1)
    frame = bytearray(ring.encode_var(10, 5, 1))
    frame[5] ^= 1
    crc = ring.decode(bytes(3) + frame)
    assert [e.to_dict() for e in crc] == [{"event": "frame_error", "position": 0, "reason": "stray_data"},
                                          {"event": "crc_error", "position": 3, "hops": 1, "vr": 5}]


def test_an_open_message_is_unfinished_at_the_end_or_lost_to_an_idle_line():
    decoder = ring.Decoder()
    assert decoder.feed(b"\x00\x91HEL") == [ring.decode(b"\x00")[0]]
    assert decoder.in_message
    (unfinished,) = decoder.finish()
    assert unfinished.to_dict() == {"event": "unfinished", "position": 1}
    assert unfinished.status is None and unfinished.type is None
    assert not decoder.in_message and decoder.finish() == []
    decoder.feed(b"\x91HEL")
    (idle,) = decoder.line_idle()
    assert (idle.reason, idle.position) == ("idle_line", 5)
    assert decoder.line_idle() == []


def test_the_decoder_reads_any_buffer_in_place():
    data = bytearray(ring.encode_print(11, "HELLO") * 3)
    view = memoryview(data)
    decoder = ring.Decoder()
    assert [e.text for e in decoder.feed(view[:10])] == ["HELLO"]
    import array
    assert [e.text for e in decoder.feed(array.array("B", data[10:]))] == ["HELLO", "HELLO"]
    with pytest.raises(TypeError):
        decoder.feed("91 48 90")
    with pytest.raises(TypeError):
        decoder.feed(None)
    with pytest.raises((TypeError, BufferError)):
        decoder.feed(memoryview(bytes(8))[::2])  # not contiguous


def test_a_profile_decodes_what_the_tool_decodes_with_it(run_cli, tmp_path):
    text = ('{"trionet_profile": 1, "ring": {"crc": {"polynomial": "0x8005", "reflect_in": true, '
            '"reflect_out": true}, "vr_group_order": "most_significant_first", '
            '"value_group_order": "most_significant_first"}}')
    path = tmp_path / "hidden.json"
    path.write_text(text)
    profile = trionet.Profile.from_file(path)
    frame = ring.encode_var(10, 300, -7.25, profile=profile)
    assert frame.hex(" ") == run_cli(["ring", "encode", "var", "--to", "10", "--vr", "300", "--value", "-7.25",
                                      "--profile", str(path)]).strip()
    data = frame + ring.encode_var(10, 300, -7.25)
    assert [e.to_dict() for e in ring.decode(data, profile=profile)] == cli_events(run_cli, data, str(path))
    assert ring.decode(frame, profile=profile)[0].value == -7.25
    assert ring.decode(frame)[0].event == "crc_error"


def test_print_text_longer_than_a_decoder_takes_is_refused_as_the_tool_does(run_cli, tmp_path):
    assert len(ring.encode_print(10, "A" * 256)) == 258
    with pytest.raises(trionet.StatusError, match="257 characters"):
        ring.encode_print(10, "A" * 257)
    run_cli(["ring", "encode", "print", "--to", "10", "A" * 257], status=2)
    path = tmp_path / "short.json"
    path.write_text('{"trionet_profile": 1, "ring": {"max_characters": 100}}')
    profile = trionet.Profile.from_file(path)
    assert len(ring.encode_print(10, "A" * 100, profile=profile)) == 102
    with pytest.raises(trionet.StatusError, match="at most 100"):
        ring.encode_print(10, "A" * 101, profile=profile)
    run_cli(["ring", "encode", "print", "--to", "10", "A" * 101, "--profile", str(path)], status=2)
    # The hop-level encoder still makes a long frame when asked (tests of decoders).
    assert len(ring.encode(ring.Message.characters(1, "A" * 257))) == 259


@pytest.mark.parametrize("text", ["895654.974", "-895654.974", "2.345", "0.5", "-0.00000000005", "1e-11",
                                  "2147483647.99999999977", "-2147483648", "+1e3", ".5", "123456.0000000001164"])
def test_a_decimal_value_gives_the_tools_frame_exactly(run_cli, text):
    # The tool rounds the decimal it reads, not the float nearest to it (895654.974 as a float is an exact
    # tie at 2**-32; the decimal is not).
    frame = ring.encode_var(10, 1, decimal.Decimal(text))
    assert frame.hex(" ") == run_cli(["ring", "encode", "var", "--to", "10", "--vr", "1", "--value", text]).strip()
    assert ring.q32_from_decimal(text) == ring.q32_from_decimal(decimal.Decimal(text))


def test_q32_from_decimal_refuses_what_the_tool_refuses():
    assert ring.q32_from_float(895654.974) - ring.q32_from_decimal("895654.974") == 1
    for text in ["2147483648", "-2147483648.0000000002", "1e10", "Infinity"]:
        with pytest.raises(trionet.StatusError):
            ring.q32_from_decimal(decimal.Decimal(text))
    with pytest.raises(trionet.StatusError):
        ring.q32_from_decimal(decimal.Decimal("NaN"))
    for text in ["", "1 ", "0x10", "nan", "1_000", "--1"]:
        with pytest.raises(ValueError):
            ring.q32_from_decimal(text)
    with pytest.raises(TypeError):
        ring.q32_from_decimal(1.5)
    assert ring.q32_from_decimal("1e-400") == 0
