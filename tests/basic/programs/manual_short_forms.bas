' Forms the manual gives that read differently from the rest: DP, DEFPOS's alternate format (MC216
' edition, 8-30), and a PRINT whose string stands in parentheses, as published programs write it.
'@ ring: this mc
DP(100)
WAIT UNTIL OFFPOS=0
PRINT("position ");DPOS[6,1]
