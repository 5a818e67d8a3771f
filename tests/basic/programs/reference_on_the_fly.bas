' A feed axis given a new reference while it moves: DEFPOS half way through an index
' move, then OFFPOS at rest, then a position tested against a threshold in mm.
'@ ring: this mc
BASE(0)
UNITS=1: SPEED=100: ACCEL=1000: DECEL=1000
MOVE(100)
WA(500)
PRINT "before: ";DPOS
DEFPOS(0)                  ' takes effect at the next servo tick, the move going on
PRINT "OFFPOS ";OFFPOS;", DPOS ";DPOS
WAIT UNTIL OFFPOS=0        ' as the manual advises before using the new position
PRINT "after: ";DPOS[6,2]
WAIT IDLE
PRINT "end: ";DPOS
OFFPOS=-DPOS               ' the same as DEFPOS(0)
WAIT UNTIL OFFPOS=0
PRINT "zeroed: ";DPOS
UNITS=1000: SPEED=100: ACCEL=1000: DECEL=1000
TICKS=0
MOVE(100)
WAIT UNTIL MPOS>50
PRINT "past 50 at ";MPOS;" after ";-TICKS;" ms"
