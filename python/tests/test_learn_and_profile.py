"""trionet.learn and trionet.Profile against `trionet ring learn`, `trionet genius learn` and
`trionet profile show`."""

import json

import pytest

import trionet
from trionet import genius, learn, ring

HIDDEN = ('{"trionet_profile": 1, "ring": {"crc": {"polynomial": "0x8005", "reflect_in": true, "reflect_out": true},'
          ' "vr_group_order": "most_significant_first", "value_group_order": "most_significant_first"}}')
SENT = [(1, 12.5), (300, -7.25), (16000, 1000000.125), (42, 0.001)]


def test_the_ring_crc_is_learned_from_a_capture_as_the_tool_learns_it(run_cli, tmp_path):
    hidden = trionet.Profile.from_json(HIDDEN)
    capture = b"".join(ring.encode_var(10, vr, value, profile=hidden) for vr, value in SENT)
    (tmp_path / "captured.hex").write_text(capture.hex(" "))
    r = learn.learn_ring_crc(capture)
    assert r.status is learn.CrcLearnStatus.ok and r.frames == 4
    assert (r.crc.polynomial, r.crc.initial, r.crc.reflect_in, r.crc.reflect_out, r.crc.name) == \
        (0x8005, 0xFFFF, True, True, "CRC-16/MODBUS")
    events = [json.loads(line) for line in run_cli(["ring", "learn", "crc", str(tmp_path / "captured.hex")]).splitlines()]
    assert events[0]["name"] == r.crc.name and int(events[0]["polynomial"], 16) == r.crc.polynomial
    assert events[-1]["survivors"] == r.survivors


def test_the_layout_is_learned_from_a_capture_and_what_was_sent():
    hidden = trionet.Profile.from_json(HIDDEN)
    frames, skipped = learn.variable_transfers(b"\x01" + b"".join(ring.encode_var(10, v, x, profile=hidden)
                                                                   for v, x in SENT))
    assert len(frames) == 4 and skipped == 1
    r = learn.learn_ring_layout(frames, SENT)
    assert r and r.vr_group_order is learn.GroupOrder.most_significant_first
    assert r.value_group_order is learn.GroupOrder.most_significant_first
    assert sum(fit.fits for fit in r.orders) == 1


def test_too_few_frames_are_a_status_not_an_exception():
    r = learn.learn_ring_crc([ring.encode_var(10, 1, 1.0)[1:-1]])
    assert r.status is learn.CrcLearnStatus.too_many_candidates and r.crc is None and not r
    assert learn.learn_ring_crc(b"").status is learn.CrcLearnStatus.no_frames
    with pytest.raises(ValueError):
        learn.learn_ring_crc([b"short"])


def test_the_genius_crc_is_learned_from_transmissions():
    profile = trionet.Profile.from_json('{"trionet_profile": 1, "genius": {"crc6": {"polynomial": "0x2f", '
                                        '"initial": "0x3f", "reflect_in": false, "reflect_out": false, '
                                        '"xor_out": "0x00"}}}')
    characters = []
    for i in range(6):
        t = genius.Transmission(i, (genius.Segment(bytes(range(i, i + 1 + i % 3))),), destination=(i + 3) % 32)
        characters += genius.encode_transmission(t, profile=profile)
    stops, blocks, skipped = learn.genius_crc_samples(characters, profile=profile)
    assert len(stops) == 6 and blocks == [] and skipped == 0
    r = learn.learn_genius_crc(stops)
    assert r.status is learn.CrcLearnStatus.ok
    assert (r.crc.polynomial, r.crc.reflect_in) == (0x2F, False)
    assert all(genius.crc6(s.data, profile=profile) == s.crc for s in stops)


def test_a_profile_reads_writes_and_says_what_is_wrong(run_cli, tmp_path):
    default = trionet.Profile()
    assert json.loads(default.to_json()) == json.loads(run_cli(["profile", "show"]))
    p = trionet.Profile.from_json(HIDDEN)
    assert p != default and trionet.Profile.from_json(p.to_json()) == p
    path = tmp_path / "p.json"
    path.write_text(HIDDEN)
    assert json.loads(run_cli(["profile", "show", str(path)])) == p.to_dict()
    assert "namespace plant" in p.header("plant")
    with pytest.raises(ValueError):
        p.header("not a name")
    for name, why in (("int", "keyword"), ("trionet", "trionet")):  # headers that would not compile
        with pytest.raises(ValueError, match=f"namespace '{name}' cannot be used: .*{why}"):
            p.header(name)
    with pytest.raises(trionet.ProfileError) as raised:
        trionet.Profile.from_json('{"trionet_profile": 1, "ring": {"crc": {"polynomial": "0x10000"}}}')
    assert raised.value.key == "ring.crc.polynomial" and raised.value.status.name == "out_of_range"
    with pytest.raises(trionet.ProfileError) as raised:
        trionet.Profile.from_json("{")
    assert raised.value.status.name == "not_json" and raised.value.line == 1
    with pytest.raises(trionet.ProfileError):
        trionet.Profile.from_json(b"\xff\xfe")
    with pytest.raises(TypeError):
        ring.Decoder(profile="hidden.json")


def test_a_profile_with_invalid_utf8_or_over_1_mib_is_refused_as_the_tool_refuses_it(run_cli, tmp_path):
    bad = b'{"trionet_profile": 1, "name": "\xff"}'
    with pytest.raises(trionet.ProfileError) as raised:
        trionet.Profile.from_json(bad)
    assert raised.value.status.name == "not_json" and raised.value.column == 33
    assert raised.value.message == "syntax: invalid UTF-8"
    path = tmp_path / "bad.json"
    path.write_bytes(bad)
    with pytest.raises(trionet.ProfileError):
        trionet.Profile.from_file(path)
    run_cli(["profile", "show", str(path)], status=2)
    big = tmp_path / "big.json"
    big.write_bytes(b'{"trionet_profile": 1, "name": "' + b"x" * (2 << 20) + b'"}')
    with pytest.raises(trionet.ProfileError, match="too_large"):
        trionet.Profile.from_file(big)
    exact = tmp_path / "exact.json"  # 1 MiB exactly is read
    head = b'{"trionet_profile": 1, "name": "'
    exact.write_bytes(head + b"x" * ((1 << 20) - len(head) - 2) + b'"}')
    assert len(trionet.Profile.from_file(exact).name) == (1 << 20) - len(head) - 2
    assert trionet.Profile.from_json(bytearray(b'{"trionet_profile": 1, "name": "caf\xc3\xa9"}')).name == "caf\u00e9"
    for wrong in (None, 5):
        with pytest.raises(TypeError):
            trionet.Profile.from_json(wrong)
