' Machine start-up: enable the drive, set axis 0 up in mm, home it, then go to the
' work position and report where it is and how long the move took.
'@ ring: this mc
WDOG=ON
BASE(0)
UNITS=1000          ' 1000 encoder edges a mm
SPEED=50: ACCEL=500: DECEL=500: CREEP=10
SERVO=ON
DEFPOS(-20)         ' where the axis finds itself at power-up
DATUM(3)            ' home: simplified by the simulator to a move to 0 at CREEP
WAIT IDLE
PRINT "homed at ";MPOS
start=TICKS
MOVEABS(100)
WA(1000)
PRINT "half way: MTYPE ";MTYPE[1,0];", at ";MPOS[6,2];", ";REMAIN[6,2];" to go"
WAIT IDLE
PRINT "at ";MPOS[6,1];" mm after ";start-TICKS;" ms"
PRINT "MTYPE ";MTYPE;" IDLE ";IDLE
