-- trionet_ring.lua: Wireshark dissector for the Trio Motion Coordinator fibre-optic ring
-- (docs/protocol.md 1.2-1.4). Wireshark 4.0 and later.
--
-- trionet writes each message that crossed a link as one LINKTYPE_WIRESHARK_UPPER_PDU record whose
-- exported-PDU tag names this dissector ("trionet_ring"), so Wireshark calls it with no preference set
-- (docs/wireshark.md). A record is one message (header .. end of message), a message cut short, a run of
-- stray data bytes or a stray end of message; a record holding several of these is shown part by part.
--
--   header   1 | A: hops 1..15 | T: type 1..7        end of message   1 | A | 0 0 0       data   0 | 7 bits
--   T = 2:   V0 V1 | X0 .. X9 | C0 C1   (7-bit groups, least significant first; CRC over V0..X9)
--
-- Each part is checked as the library's decoder checks it at the destination, in the same order:
-- end-of-message A, type, length, CRC (type 2), fields. The fields and their names are those of the
-- library's record view (src/host/trionet/host/capture_view.hpp), and tests compare the two.

local ring = Proto("trionet_ring", "Trio fibre-optic ring")

-- Lua BitOp ("bit"), which every Wireshark with Lua provides (Lua 5.2 .. 5.4); values here stay below 2^31.
local band, bor, bxor, lshift, rshift = bit.band, bit.bor, bit.bxor, bit.lshift, bit.rshift

local message_types = {
  [1] = "character transfer",
  [2] = "direct variable transfer",
  [3] = "keypad offset",
  [4] = "keypad mode",
  [5] = "reserved",
  [6] = "reserved",
  [7] = "reserved",
}

local f = {
  header = ProtoField.uint8("trionet_ring.header", "Header", base.HEX),
  hops = ProtoField.uint8("trionet_ring.hops", "Hops (A)", base.DEC, nil, 0x78),
  type = ProtoField.uint8("trionet_ring.type", "Type (T)", base.DEC, message_types, 0x07),
  length = ProtoField.uint16("trionet_ring.length", "Data bytes", base.DEC),
  data = ProtoField.bytes("trionet_ring.data", "Data"),
  eom = ProtoField.uint8("trionet_ring.eom", "End of message", base.HEX),
  eom_hops = ProtoField.uint8("trionet_ring.eom_hops", "Hops (A)", base.DEC, nil, 0x78),
  text = ProtoField.string("trionet_ring.text", "Text"),
  vr = ProtoField.uint16("trionet_ring.vr", "VR", base.DEC),
  value_raw = ProtoField.int64("trionet_ring.value_raw", "Value, Q32.32 raw", base.DEC),
  value = ProtoField.double("trionet_ring.value", "Value"),
  crc = ProtoField.uint16("trionet_ring.crc", "CRC (the 14 bits sent)", base.HEX),
  crc_computed = ProtoField.uint16("trionet_ring.crc_computed", "CRC computed", base.HEX),
  crc_good = ProtoField.bool("trionet_ring.crc_good", "CRC good"),
  offset = ProtoField.uint8("trionet_ring.offset", "Keypad offset (hops)", base.DEC),
  mode = ProtoField.uint8("trionet_ring.mode", "Keypad mode", base.DEC,
                          { [0] = "key ON only", [127] = "key ON and key OFF" }),
  status = ProtoField.string("trionet_ring.status", "Status"),
  frame_error = ProtoField.string("trionet_ring.frame_error", "Frame error"),
}
ring.fields = { f.header, f.hops, f.type, f.length, f.data, f.eom, f.eom_hops, f.text, f.vr, f.value_raw,
                f.value, f.crc, f.crc_computed, f.crc_good, f.offset, f.mode, f.status, f.frame_error }

local function frame_error_expert(reason, text)
  return ProtoExpert.new("trionet_ring.expert." .. reason, "Frame error: " .. text, expert.group.MALFORMED,
                         expert.severity.ERROR)
end
local experts = {
  crc_error = ProtoExpert.new("trionet_ring.expert.crc_error", "CRC error: the variable is not written",
                              expert.group.CHECKSUM, expert.severity.ERROR),
  stray_data = frame_error_expert("stray_data", "data bytes outside any message"),
  stray_eom = frame_error_expert("stray_eom", "end of message with no open message"),
  interrupted = frame_error_expert("interrupted", "message cut short before its end of message"),
  eom_mismatch = frame_error_expert("eom_mismatch", "end of message hops differ from the header's"),
  bad_length = frame_error_expert("bad_length", "data length wrong for the message type"),
  bad_field = frame_error_expert("bad_field", "field out of range (offset, mode, or X9 bits 6..1)"),
  unknown_type = frame_error_expert("unknown_type", "message type 5..7 (reserved)"),
  zero_hops = frame_error_expert("zero_hops", "header with hops A = 0"),
}
ring.experts = { experts.crc_error, experts.stray_data, experts.stray_eom, experts.interrupted,
                 experts.eom_mismatch, experts.bad_length, experts.bad_field, experts.unknown_type,
                 experts.zero_hops }

ring.prefs.max_characters = Pref.uint("Longest character transfer", 256,
  "Characters a character transfer may carry (the decoder's MaxCharacters; default 256)")
ring.prefs.crc_polynomial = Pref.string("CRC polynomial", "0x1021",
  "16-bit CRC polynomial, not reflected (default CRC-16/CCITT-FALSE: 0x1021)")
ring.prefs.crc_initial = Pref.string("CRC initial value", "0xFFFF", "CRC register before the first byte")
ring.prefs.crc_xorout = Pref.string("CRC final XOR", "0x0000", "XOR applied to the CRC at the end")

local function pref_number(text, default)
  local n = tonumber(text)
  if n == nil or n < 0 or n > 0xFFFF then return default end
  return n
end

-- The CRC over data[from .. from + count - 1], as the library's crc16<Polynomial, Initial, XorOut>.
local function crc16(data, from, count)
  local poly = pref_number(ring.prefs.crc_polynomial, 0x1021)
  local crc = pref_number(ring.prefs.crc_initial, 0xFFFF)
  for i = from, from + count - 1 do
    crc = bxor(crc, lshift(data[i], 8))
    for _ = 1, 8 do
      if band(crc, 0x8000) ~= 0 then
        crc = band(bxor(lshift(crc, 1), poly), 0xFFFF)
      else
        crc = band(lshift(crc, 1), 0xFFFF)
      end
    end
  end
  return band(bxor(crc, pref_number(ring.prefs.crc_xorout, 0)), 0xFFFF)
end

-- The characters with \\, \r, \n, \t and \xNN escaped, so that every character (NUL too) shows; the byte
-- after ESC 'H' is a display position, a number: always \xNN.
local function escaped_text(data, from, count)
  local out = {}
  for i = from, from + count - 1 do
    local c = data[i]
    if i >= from + 2 and data[i - 2] == 27 and data[i - 1] == 72 then
      out[#out + 1] = string.format("\\x%02x", c)
    elseif c == 92 then
      out[#out + 1] = "\\\\"
    elseif c == 13 then
      out[#out + 1] = "\\r"
    elseif c == 10 then
      out[#out + 1] = "\\n"
    elseif c == 9 then
      out[#out + 1] = "\\t"
    elseif c < 32 or c >= 127 then
      out[#out + 1] = string.format("\\x%02x", c)
    else
      out[#out + 1] = string.char(c)
    end
  end
  return table.concat(out)
end

local function is_data(byte) return byte < 0x80 end
local function is_eom(byte) return byte >= 0x80 and band(byte, 7) == 0 end
local function hops_of(byte) return band(rshift(byte, 3), 15) end

-- What the decoder reports for one part (bytes data[from .. to]): status and frame error reason.
local function check_unit(data, from, to)
  local first = data[from]
  if is_data(first) then return "frame_error", "stray_data" end
  if is_eom(first) then return "frame_error", "stray_eom" end
  local hops = hops_of(first)
  if hops == 0 then return "frame_error", "zero_hops" end
  if to == from or not is_eom(data[to]) then return "frame_error", "interrupted" end
  if hops_of(data[to]) ~= hops then return "frame_error", "eom_mismatch" end
  local t = band(first, 7)
  if t > 4 then return "frame_error", "unknown_type" end
  local length = to - from - 1
  local d = from + 1
  if t == 1 then
    if length == 0 or length > ring.prefs.max_characters then return "frame_error", "bad_length" end
    return "message"
  elseif t == 2 then
    if length ~= 14 then return "frame_error", "bad_length" end
    -- X9 bits 6..1 make a frame error whatever the CRC: a CRC error is an otherwise well-formed message.
    if band(data[d + 11], 0x7E) ~= 0 then return "frame_error", "bad_field" end
    if band(crc16(data, d, 12), 0x7F7F) ~= bor(data[d + 12], lshift(data[d + 13], 8)) then
      return "crc_error"
    end
    return "message"
  elseif t == 3 then
    if length ~= 1 then return "frame_error", "bad_length" end
    if data[d] < 1 or data[d] > 15 then return "frame_error", "bad_field" end
    return "message"
  else
    if length ~= 1 then return "frame_error", "bad_length" end
    if data[d] ~= 0 and data[d] ~= 127 then return "frame_error", "bad_field" end
    return "message"
  end
end

-- The Q32.32 value of X0..X9 at data[at .. at + 9]: 7-bit groups, least significant first.
local function q32_of(data, at)
  local bits = Int64.new(0)
  for k = 9, 0, -1 do bits = bits:lshift(7):bor(Int64.new(data[at + k])) end
  return bits
end

-- Adds one part's fields under `tree`; returns a summary for the Info column.
local function dissect_unit(tvb, tree, data, from, to)
  local first = data[from]
  local message = not is_data(first) and not is_eom(first)
  local ends = is_eom(data[to])
  local data_at = message and from + 1 or from
  local data_end = ends and to - 1 or to
  local length = data_end - data_at + 1
  if length < 0 then length = 0 end
  local status, reason = check_unit(data, from, to)
  local t = band(first, 7)
  local hops = hops_of(first)

  local summary
  if status == "frame_error" then
    summary = "Frame error: " .. reason
  elseif status == "crc_error" then
    summary = "CRC error"
  else
    summary = string.format("hops %d, %s", hops, message_types[t])
  end
  local unit = tree:add(tvb(from - 1, to - from + 1), "")

  if message then
    local header = unit:add(f.header, tvb(from - 1, 1))
    header:add(f.hops, tvb(from - 1, 1))
    header:add(f.type, tvb(from - 1, 1))
  end
  local whole = tvb(from - 1, to - from + 1)
  if message or length > 0 then unit:add(f.length, whole, length) end
  if length > 0 then unit:add(f.data, tvb(data_at - 1, length)) end
  if ends then
    local eom = unit:add(f.eom, tvb(to - 1, 1))
    eom:add(f.eom_hops, tvb(to - 1, 1))
  end
  if message and hops ~= 0 then
    if t == 1 and length > 0 then
      local text = escaped_text(data, data_at, length)
      unit:add(f.text, tvb(data_at - 1, length), text)
      if status == "message" then summary = string.format("hops %d, PRINT \"%s\"", hops, text) end
    elseif t == 2 and length == 14 then
      local vr = data[data_at] + data[data_at + 1] * 128
      local raw = q32_of(data, data_at + 2)
      local value = raw:tonumber() / 4294967296
      local computed = band(crc16(data, data_at, 12), 0x7F7F)
      local received = bor(data[data_at + 12], lshift(data[data_at + 13], 8))
      unit:add(f.vr, tvb(data_at - 1, 2), vr)
      unit:add(f.value_raw, tvb(data_at + 1, 10), raw)
      unit:add(f.value, tvb(data_at + 1, 10), value)
      unit:add(f.crc, tvb(data_at + 11, 2), received)
      unit:add(f.crc_computed, tvb(data_at + 11, 2), computed)
      unit:add(f.crc_good, tvb(data_at + 11, 2), received == computed)
      if status == "message" then
        summary = string.format("hops %d, VR(%d) = %s", hops, vr, tostring(value))
      elseif status == "crc_error" then
        summary = string.format("hops %d, CRC error, VR(%d)", hops, vr)
      end
    elseif t == 3 and length == 1 then
      unit:add(f.offset, tvb(data_at - 1, 1))
      if status == "message" then summary = string.format("hops %d, keypad offset %d", hops, data[data_at]) end
    elseif t == 4 and length == 1 then
      unit:add(f.mode, tvb(data_at - 1, 1))
      if status == "message" then summary = string.format("hops %d, keypad mode %d", hops, data[data_at]) end
    end
  end
  unit:set_text(summary)
  unit:add(f.status, whole, status)
  if status == "frame_error" then
    unit:add(f.frame_error, whole, reason)
    unit:add_proto_expert_info(experts[reason])
  elseif status == "crc_error" then
    unit:add_proto_expert_info(experts.crc_error)
  end
  return summary
end

local interface_name = Field.new("frame.interface_name")

-- The Source and Destination columns: the two ends of the link the record crossed, from the interface's name.
-- A ring link runs from one node to the next, so a live capture's port is the receiving or the sending end.
local function link_ends()
  local field = interface_name()
  local name = field and field.value or ""
  local from, to = name:match("^link %d+: (.-) %-> (.+)$")
  if from ~= nil then return from, to end
  local port = name:match("^received on (.+)$")
  if port ~= nil then return "previous node", port end
  port = name:match("^sent on (.+)$")
  if port ~= nil then return port, "next node" end
  if name == "" then name = "ring link" end
  return name, "next node"
end

function ring.dissector(tvb, pinfo, tree)
  local n = tvb:len()
  if n == 0 then return 0 end
  pinfo.cols.protocol = "TRIO RING"
  pinfo.cols.src, pinfo.cols.dst = link_ends()
  local data = {}
  for i = 1, n do data[i] = tvb(i - 1, 1):uint() end
  local root = tree:add(ring, tvb())

  -- Cut the record into parts as the capture writer cuts a link: a header begins a message, an end of
  -- message ends it (or stands alone), data outside a message is a stray run up to the next control byte.
  local summaries = {}
  local start = nil
  local open = nil  -- "message" or "stray"
  local function close(last)
    if open ~= nil then summaries[#summaries + 1] = dissect_unit(tvb, root, data, start, last) end
    open = nil
  end
  for i = 1, n do
    local b = data[i]
    if is_data(b) then
      if open == nil then
        start, open = i, "stray"
      end
    elseif not is_eom(b) then
      close(i - 1)
      start, open = i, "message"
    elseif open == "message" then
      close(i)
    else
      close(i - 1)
      start, open = i, "stray"
      close(i)
    end
  end
  close(n)
  pinfo.cols.info = table.concat(summaries, "; ")
  return n
end
