-- trionet_can.lua: Wireshark dissector for Trio's CANbus VR exchange, application note TN20-17
-- (docs/protocol.md 2.1-2.2). Wireshark 4.0 and later.
--
-- It sits on Wireshark's own SocketCAN dissector (LINKTYPE_CAN_SOCKETCAN captures from candump, dumpcap,
-- tcpdump or trionet): it registers every exchange identifier of a bus of N controllers (preference, default
-- 5) in the "can.id" table. A standard data frame of DLC 8 on such an identifier is a VR message:
--
--   identifier 10 d + r - 1: to node d, on its receive channel r, from the r-th other node in ascending order
--   byte 0 VR | 1 sign (0 or 1) | 2..5 integer part, big-endian | 6..7 fraction in ten-thousandths, big-endian
--
-- Any other frame (another identifier, remote, extended, another length) is left to Wireshark. The field
-- names are those of the library's record view (src/host/trionet/host/capture_view.hpp).

local exchange = Proto("trionet_can", "Trio TN20-17 VR exchange")

local f = {
  sender = ProtoField.uint8("trionet_can.sender", "Sender node", base.DEC),
  receiver = ProtoField.uint8("trionet_can.receiver", "Receiver node", base.DEC),
  receive_channel = ProtoField.uint8("trionet_can.receive_channel", "Receive channel", base.DEC),
  vr = ProtoField.uint8("trionet_can.vr", "VR", base.DEC),
  sign = ProtoField.uint8("trionet_can.sign", "Sign", base.DEC, { [0] = "zero or positive", [1] = "negative" }),
  integer = ProtoField.uint32("trionet_can.integer", "Integer part", base.DEC),
  fraction = ProtoField.uint16("trionet_can.fraction", "Fraction (ten-thousandths)", base.DEC),
  value = ProtoField.double("trionet_can.value", "Value"),
  error = ProtoField.string("trionet_can.error", "Error"),
}
exchange.fields = { f.sender, f.receiver, f.receive_channel, f.vr, f.sign, f.integer, f.fraction, f.value,
                    f.error }

local experts = {
  bad_sign = ProtoExpert.new("trionet_can.expert.bad_sign", "Sign byte is neither 0 nor 1", expert.group.MALFORMED,
                             expert.severity.ERROR),
  bad_fraction = ProtoExpert.new("trionet_can.expert.bad_fraction", "Fraction above 9999", expert.group.MALFORMED,
                             expert.severity.ERROR),
}
exchange.experts = { experts.bad_sign, experts.bad_fraction }

exchange.prefs.node_count = Pref.uint("Controllers on the bus", 5,
  "TN20-17 node count N (2..11; the note's 5 by default): identifiers 10 d + r - 1 for d = 1..N, r = 1..N-1")

local can_rtr = Field.new("can.flags.rtr")
local can_len = Field.new("can.len")
local can_reserved = Field.new("can.reserved")

local function node_count()
  local n = exchange.prefs.node_count
  if n < 2 or n > 11 then return 5 end
  return n
end

-- Sender, receiver and receive channel of `identifier` on a bus of n nodes, or nil.
local function route_of(n, identifier)
  local receiver = math.floor(identifier / 10)
  local channel = identifier - receiver * 10 + 1
  if receiver < 1 or receiver > n or channel >= n then return nil end
  local sender = channel
  if channel >= receiver then sender = channel + 1 end
  return sender, receiver, channel
end

function exchange.dissector(tvb, pinfo, tree)
  local rtr, length, reserved = can_rtr(), can_len(), can_reserved()
  if rtr == nil or rtr.value or length == nil or length.value ~= 8 or tvb:len() < 8 then return 0 end
  if reserved ~= nil and reserved.len >= 2 then
    local len8_dlc = reserved.range:range(1, 1):uint()  -- a DLC of 9..15 is not exactly 8
    if len8_dlc > 8 and len8_dlc <= 15 then return 0 end
  end
  local sender, receiver, channel = route_of(node_count(), pinfo.match_uint)
  if sender == nil then return 0 end

  pinfo.cols.protocol = "TN20-17"
  pinfo.cols.src = string.format("node %d", sender)
  pinfo.cols.dst = string.format("node %d", receiver)
  local root = tree:add(exchange, tvb(0, 8))
  root:add(f.sender, tvb(0, 0), sender)
  root:add(f.receiver, tvb(0, 0), receiver)
  root:add(f.receive_channel, tvb(0, 0), channel)
  root:add(f.vr, tvb(0, 1))
  root:add(f.sign, tvb(1, 1))
  root:add(f.integer, tvb(2, 4))
  root:add(f.fraction, tvb(6, 2))
  local vr, sign, integer, fraction = tvb(0, 1):uint(), tvb(1, 1):uint(), tvb(2, 4):uint(), tvb(6, 2):uint()
  local error, problem = nil, nil
  if sign > 1 then
    error, problem = "bad_sign", string.format("sign byte %d is neither 0 nor 1", sign)
  elseif fraction > 9999 then
    error, problem = "bad_fraction", string.format("fraction %d is above 9999", fraction)
  end
  if error == nil then
    local value = (integer * 10000 + fraction) / 10000
    local text = string.format("%d.%04d", integer, fraction)
    if sign == 1 then
      value = -value
      text = "-" .. text
    end
    root:add(f.value, tvb(1, 7), value):set_text("Value: " .. text)
    pinfo.cols.info = string.format("node %d -> node %d: VR(%d) = %s", sender, receiver, vr, text)
  else
    root:add(f.error, tvb(0, 8), error)
    root:add_proto_expert_info(experts[error])
    pinfo.cols.info = string.format("node %d -> node %d: VR(%d), %s", sender, receiver, vr, problem)
  end
  return 8
end

-- The identifiers registered in can.id, kept so that a new node count replaces them.
local registered = {}
local function register_identifiers()
  local table_ = DissectorTable.get("can.id")
  for _, identifier in ipairs(registered) do table_:remove(identifier, exchange) end
  registered = {}
  local n = node_count()
  for receiver = 1, n do
    for channel = 1, n - 1 do
      local identifier = 10 * receiver + channel - 1
      table_:add(identifier, exchange)
      registered[#registered + 1] = identifier
    end
  end
end

function exchange.prefs_changed()
  register_identifiers()
end

register_identifiers()
