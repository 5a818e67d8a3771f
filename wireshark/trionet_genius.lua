-- trionet_genius.lua: Wireshark dissector for GE Genius bus characters and transmissions
-- (docs/protocol.md 3.1-3.2, the control-character layout of docs/genius.md). Wireshark 4.0 and later.
--
-- trionet writes each transmission as one LINKTYPE_WIRESHARK_UPPER_PDU record whose exported-PDU tag names
-- this dissector ("trionet_genius"), so Wireshark calls it with no preference set (docs/wireshark.md). Every
-- character is a 16-bit big-endian word holding the 11-bit wire word:
--
--   bit   15..11   10      9 .. 2            1          0
--         0        stop 1  byte (d7 .. d0)   control    start 0
--
--   Start          control 00 B sssss   (B = 1 broadcast; sssss the sender's SBA)
--   Stop           control 01 cccccc    (CRC-6 of every data byte since the Start)
--   Start of block control 10 0 ddddd   (destination SBA)
--   End of block   control 11 cccccc    (CRC-6 of the block's data bytes)
--
-- A record is one transmission (Start .. Stop), a transmission cut short, characters outside a
-- transmission, or one badly framed word; a record holding several is shown part by part, each through a
-- fresh parser that follows the library's transmission_parser exactly (capacities and CRC as preferences).
-- The field names are those of the library's record view (src/host/trionet/host/capture_view.hpp).

local genius = Proto("trionet_genius", "GE Genius bus")

-- Lua BitOp ("bit"), which every Wireshark with Lua provides (Lua 5.2 .. 5.4); values here stay below 2^31.
local band, bor, bxor, lshift, rshift = bit.band, bit.bor, bit.bxor, bit.lshift, bit.rshift

local f = {
  word = ProtoField.uint16("trionet_genius.word", "Character", base.HEX),
  start_bit = ProtoField.uint16("trionet_genius.start_bit", "Start bit", base.DEC, nil, 0x0001),
  control = ProtoField.bool("trionet_genius.control", "Control character", 16, nil, 0x0002),
  byte = ProtoField.uint16("trionet_genius.byte", "Byte", base.HEX, nil, 0x03FC),
  stop_bit = ProtoField.uint16("trionet_genius.stop_bit", "Stop bit", base.DEC, nil, 0x0400),
  character_status = ProtoField.string("trionet_genius.character_status", "Framing error"),
  kind = ProtoField.string("trionet_genius.kind", "Kind"),
  broadcast = ProtoField.bool("trionet_genius.broadcast", "Broadcast"),
  sender = ProtoField.uint8("trionet_genius.sender", "Sender SBA", base.DEC),
  destination = ProtoField.uint8("trionet_genius.destination", "Destination SBA (directed)", base.DEC),
  block_destination = ProtoField.uint8("trionet_genius.block_destination", "Block destination SBA", base.DEC),
  crc = ProtoField.uint8("trionet_genius.crc", "CRC-6", base.DEC),
  crc_computed = ProtoField.uint8("trionet_genius.crc_computed", "CRC-6 computed", base.DEC),
  crc_good = ProtoField.bool("trionet_genius.crc_good", "CRC-6 good"),
  block_crc = ProtoField.uint8("trionet_genius.block_crc", "Block CRC-6", base.DEC),
  block_crc_computed = ProtoField.uint8("trionet_genius.block_crc_computed", "Block CRC-6 computed", base.DEC),
  block_crc_good = ProtoField.bool("trionet_genius.block_crc_good", "Block CRC-6 good"),
  parse_status = ProtoField.string("trionet_genius.parse_status", "Parser"),
  status = ProtoField.string("trionet_genius.status", "Transmission"),
  odd_byte = ProtoField.uint8("trionet_genius.odd_byte", "Odd byte (not a character)", base.HEX),
}
genius.fields = { f.word, f.start_bit, f.control, f.byte, f.stop_bit, f.character_status, f.kind, f.broadcast,
                  f.sender, f.destination, f.block_destination, f.crc, f.crc_computed, f.crc_good, f.block_crc,
                  f.block_crc_computed, f.block_crc_good, f.parse_status, f.status, f.odd_byte }

-- One expert item per wire error the parser reports, named after its status.
local error_texts = {
  data_outside_transmission = "data character outside a transmission",
  control_outside_transmission = "control character outside a transmission",
  start_inside_transmission = "Start inside a transmission",
  unknown_control = "unknown control character",
  destination_out_of_range = "destination SBA out of range",
  missing_destination = "directed transmission without destination",
  block_not_closed = "block not closed",
  end_of_block_outside_block = "End of block outside a block",
  empty_block = "empty block",
  empty_transmission = "empty transmission",
  block_crc_mismatch = "block CRC-6 mismatch",
  stop_crc_mismatch = "Stop CRC-6 mismatch",
  overflow = "more data or blocks than the parser holds",
  framing_error = "framing error (start bit not 0, stop bit not 1, or not an 11-bit word)",
}
local experts = {}
local expert_list = {}
for status, text in pairs(error_texts) do
  local group = expert.group.MALFORMED
  if status == "block_crc_mismatch" or status == "stop_crc_mismatch" then group = expert.group.CHECKSUM end
  experts[status] = ProtoExpert.new("trionet_genius.expert." .. status, text, group, expert.severity.ERROR)
  expert_list[#expert_list + 1] = experts[status]
end
experts.incomplete = ProtoExpert.new("trionet_genius.expert.incomplete", "transmission ends without its Stop",
                                     expert.group.SEQUENCE, expert.severity.WARN)
experts.odd_length = ProtoExpert.new("trionet_genius.expert.odd_length", "record length is not a whole number of characters",
                                     expert.group.MALFORMED, expert.severity.ERROR)
expert_list[#expert_list + 1] = experts.incomplete
expert_list[#expert_list + 1] = experts.odd_length
genius.experts = expert_list

genius.prefs.data_capacity = Pref.uint("Parser data capacity", 256,
  "Data bytes per transmission the parser holds (DataCapacity; default 256)")
genius.prefs.segment_capacity = Pref.uint("Parser segment capacity", 16,
  "Segments (plain runs and blocks) per transmission the parser holds (SegmentCapacity; default 16)")
genius.prefs.crc_polynomial = Pref.uint("CRC-6 polynomial", 3, "6-bit polynomial, normal notation (default CRC-6/G-704: 3)")
genius.prefs.crc_initial = Pref.uint("CRC-6 initial value", 0, "6-bit initial value")
genius.prefs.crc_reflected_in = Pref.bool("CRC-6 reflected input", true, "Bytes enter least significant bit first")
genius.prefs.crc_reflected_out = Pref.bool("CRC-6 reflected output", true, "The result is reflected")
genius.prefs.crc_xorout = Pref.uint("CRC-6 final XOR", 0, "6-bit value XORed into the result")

-- CRC-6 as the library's crc6<Poly, Init, RefIn, RefOut, XorOut>: begin, update, finish.
local function reflect6(v)
  local out = 0
  for i = 0, 5 do
    if band(rshift(v, i), 1) ~= 0 then out = bor(out, lshift(1, 5 - i)) end
  end
  return out
end
local function crc_begin()
  local init = band(genius.prefs.crc_initial, 0x3F)
  if genius.prefs.crc_reflected_in then return reflect6(init) end
  return lshift(init, 2)
end
local function crc_update(reg, byte)
  local poly = band(genius.prefs.crc_polynomial, 0x3F)
  reg = bxor(reg, byte)
  for _ = 1, 8 do
    if genius.prefs.crc_reflected_in then
      if band(reg, 1) ~= 0 then reg = bxor(rshift(reg, 1), reflect6(poly)) else reg = rshift(reg, 1) end
    else
      if band(reg, 0x80) ~= 0 then
        reg = band(bxor(lshift(reg, 1), lshift(poly, 2)), 0xFF)
      else
        reg = band(lshift(reg, 1), 0xFF)
      end
    end
  end
  return reg
end
local function crc_finish(reg)
  local normal
  if genius.prefs.crc_reflected_in then normal = reflect6(reg) else normal = rshift(reg, 2) end
  if genius.prefs.crc_reflected_out then normal = reflect6(normal) end
  return bxor(normal, band(genius.prefs.crc_xorout, 0x3F))
end

local function well_framed(word)
  return band(word, 0xF800) == 0 and band(word, 0x0001) == 0 and band(word, 0x0400) ~= 0
end
local function control_kind(byte)
  local top = rshift(byte, 6)
  if top == 0 then return "start" end
  if top == 1 then return "stop" end
  if top == 2 then
    if band(byte, 0x20) ~= 0 then return "unknown" end
    return "start_of_block"
  end
  return "end_of_block"
end

-- The library's transmission_parser, one per part.
local parser = {}
parser.__index = parser
local function new_parser()
  return setmetatable({ open = false, resync = false, in_block = false, need_destination = false,
                        data_characters = 0, used = 0, segments = 0, last_block = false, last_length = 0,
                        stop_crc = crc_begin(), block_crc = crc_begin() }, parser)
end
function parser:fail(status)
  self.open = false
  self.resync = true
  return status
end
function parser:outside(status)
  if self.resync then return "skipped" end
  return self:fail(status)
end
function parser:framing_error()
  if not self.open and self.resync then return "skipped" end
  return self:fail("framing_error")
end
function parser:control(kind, byte)
  if kind == "start" then
    local interrupted = self.open
    self.open, self.resync, self.in_block = true, false, false
    self.need_destination = band(byte, 0x20) == 0
    self.data_characters, self.used, self.segments = 0, 0, 0
    self.stop_crc = crc_begin()
    if interrupted then return "start_inside_transmission" end
    return "in_progress"
  end
  if not self.open then return self:outside("control_outside_transmission") end
  local crc = band(byte, 0x3F)
  if kind == "start_of_block" then
    if self.need_destination then return self:fail("missing_destination") end
    if self.in_block then return self:fail("block_not_closed") end
    if self.segments == genius.prefs.segment_capacity then return self:fail("overflow") end
    self.segments = self.segments + 1
    self.last_block, self.last_length = true, 0
    self.in_block = true
    self.block_crc = crc_begin()
    return "in_progress"
  elseif kind == "end_of_block" then
    if not self.in_block then return self:fail("end_of_block_outside_block") end
    if self.last_length == 0 then return self:fail("empty_block") end
    if crc_finish(self.block_crc) ~= crc then return self:fail("block_crc_mismatch") end
    self.in_block = false
    return "in_progress"
  elseif kind == "stop" then
    if self.in_block then return self:fail("block_not_closed") end
    if self.data_characters == 0 then return self:fail("empty_transmission") end
    if crc_finish(self.stop_crc) ~= crc then return self:fail("stop_crc_mismatch") end
    self.open = false
    return "ok"
  end
  return self:fail("unknown_control")
end
function parser:data(byte)
  if not self.open then return self:outside("data_outside_transmission") end
  self.stop_crc = crc_update(self.stop_crc, byte)
  self.data_characters = self.data_characters + 1
  if self.need_destination then
    if byte > 31 then return self:fail("destination_out_of_range") end
    self.need_destination = false
    return "in_progress"
  end
  if self.used == genius.prefs.data_capacity then return self:fail("overflow") end
  if self.in_block then
    self.block_crc = crc_update(self.block_crc, byte)
  elseif self.segments == 0 or self.last_block then
    if self.segments == genius.prefs.segment_capacity then return self:fail("overflow") end
    self.segments = self.segments + 1
    self.last_block, self.last_length = false, 0
  end
  self.used = self.used + 1
  self.last_length = self.last_length + 1
  return "in_progress"
end

local function is_error(status)
  return status ~= "in_progress" and status ~= "ok" and status ~= "skipped"
end

-- One part: the words at record offsets words[from .. to] (each {offset, value}). Returns a summary and,
-- for a transmission, its ends {source, destination} (the Source and Destination columns).
local function dissect_unit(tvb, tree, words, from, to)
  local first, last = words[from], words[to]
  local unit = tree:add(tvb(first.offset, last.offset + 2 - first.offset), "")
  local p = new_parser()
  local outcome = nil
  local sender, broadcast, destination = nil, nil, nil
  for i = from, to do
    local w = words[i]
    local range = tvb(w.offset, 2)
    local byte = band(rshift(w.value, 2), 0xFF)
    local control = band(w.value, 2) ~= 0
    local label
    local item = unit:add(f.word, range)
    item:add(f.start_bit, range)
    item:add(f.control, range)
    item:add(f.byte, range)
    item:add(f.stop_bit, range)
    local status
    if not well_framed(w.value) then
      local reason = "stop_bit_not_1"
      if band(w.value, 0xF800) ~= 0 then
        reason = "not_11_bits"
      elseif band(w.value, 1) ~= 0 then
        reason = "start_bit_not_0"
      end
      item:add(f.character_status, range, reason)
      label = "framing error: " .. reason
      status = p:framing_error()
    elseif not control then
      item:add(f.kind, range, "data")
      label = string.format("data 0x%02x", byte)
      if p.open and p.need_destination then
        item:add(f.destination, range, byte)
        destination = byte
        label = label .. " (destination SBA)"
      end
      status = p:data(byte)
    else
      local kind = control_kind(byte)
      item:add(f.kind, range, kind)
      if kind == "start" then
        broadcast = band(byte, 0x20) ~= 0
        sender = band(byte, 0x1F)
        item:add(f.broadcast, range, broadcast)
        item:add(f.sender, range, sender)
        label = string.format("Start, SBA %d, %s", sender, broadcast and "broadcast" or "directed")
        destination = nil
      elseif kind == "stop" then
        item:add(f.crc, range, band(byte, 0x3F))
        label = "Stop"
      elseif kind == "start_of_block" then
        item:add(f.block_destination, range, band(byte, 0x1F))
        label = string.format("Start of block, destination SBA %d", band(byte, 0x1F))
      elseif kind == "end_of_block" then
        item:add(f.block_crc, range, band(byte, 0x3F))
        label = "End of block"
      else
        label = "unknown control character"
      end
      status = p:control(kind, byte)
      if kind == "end_of_block" and (status == "in_progress" or status == "block_crc_mismatch") then
        item:add(f.block_crc_computed, range, crc_finish(p.block_crc))
        item:add(f.block_crc_good, range, status == "in_progress")
      elseif kind == "stop" and (status == "ok" or status == "stop_crc_mismatch") then
        item:add(f.crc_computed, range, crc_finish(p.stop_crc))
        item:add(f.crc_good, range, status == "ok")
      end
    end
    if status ~= "in_progress" then
      item:add(f.parse_status, range, status)
      label = label .. ": " .. status
    end
    if is_error(status) then item:add_proto_expert_info(experts[status]) end
    if outcome == nil and (status == "ok" or is_error(status)) then outcome = status end
    item:set_text(label)
  end
  local whole = tvb(first.offset, last.offset + 2 - first.offset)
  if outcome == nil and p.open then
    outcome = "incomplete"
    unit:add_proto_expert_info(experts.incomplete)
  end
  local summary = outcome or "characters"
  if outcome ~= nil then unit:add(f.status, whole, outcome) end
  if outcome == "ok" then
    if broadcast then
      summary = string.format("SBA %d broadcast", sender)
    else
      summary = string.format("SBA %d to SBA %d", sender, destination)
    end
  end
  unit:set_text("Transmission: " .. summary)
  local ends = nil
  if sender ~= nil then
    ends = { source = string.format("SBA %d", sender), destination = "broadcast" }
    if not broadcast then
      ends.destination = destination ~= nil and string.format("SBA %d", destination) or "unknown"
    end
  end
  return summary, ends
end

function genius.dissector(tvb, pinfo, tree)
  local n = tvb:len()
  if n == 0 then return 0 end
  pinfo.cols.protocol = "GENIUS"
  local root = tree:add(genius, tvb())
  local words = {}
  for at = 0, n - 2, 2 do words[#words + 1] = { offset = at, value = tvb(at, 2):uint() } end

  -- Cut the record into parts as the capture writer cuts a line: a Start begins a transmission and its
  -- Stop ends it; characters outside a transmission run up to the next Start; a bad word stands alone.
  local summaries = {}
  local ends = nil  -- of the record's first transmission
  local start, open = nil, nil  -- open: "transmission" or "stray"
  local function close(last)
    if open ~= nil then
      local summary, unit_ends = dissect_unit(tvb, root, words, start, last)
      summaries[#summaries + 1] = summary
      ends = ends or unit_ends
    end
    open = nil
  end
  for i, w in ipairs(words) do
    if not well_framed(w.value) then
      close(i - 1)
      start, open = i, "stray"
      close(i)
    else
      local control = band(w.value, 2) ~= 0
      local kind = control and control_kind(band(rshift(w.value, 2), 0xFF)) or "data"
      if kind == "start" then
        close(i - 1)
        start, open = i, "transmission"
      elseif open == nil then
        start, open = i, "stray"
      end
      if kind == "stop" and open == "transmission" then close(i) end
    end
  end
  close(#words)
  if n % 2 ~= 0 then
    local odd = root:add(f.odd_byte, tvb(n - 1, 1))
    odd:add_proto_expert_info(experts.odd_length)
    summaries[#summaries + 1] = "odd byte"
  end
  pinfo.cols.info = table.concat(summaries, "; ")
  -- Characters outside any transmission have no sender on record.
  pinfo.cols.src = ends and ends.source or "unknown"
  pinfo.cols.dst = ends and ends.destination or "unknown"
  return n
end
