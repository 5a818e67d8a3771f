' A rotary table in degrees: REP_DIST 360 with REP_OPTION 1 keeps the position within
' 0..360 however far it turns; then a reverse jog stopped with CANCEL.
'@ ring: this mc
WDOG=ON
BASE(2)
UNITS=100: REP_DIST=360: REP_OPTION=1
SPEED=360: ACCEL=3600: DECEL=3600: SERVO=ON
MOVE(1000)               ' almost three turns
WAIT IDLE
PRINT "after 1000 degrees: ";MPOS[6,1]
REVERSE
WA(500)
CANCEL
WAIT IDLE
PRINT "after reversing: ";MPOS[6,1];" MTYPE ";MTYPE[1,0]
