' Two axes moving together: MOVE with two distances interpolates them on one path whose
' speed is the base axis's; moves are buffered, and WAIT LOADED lets the next one in.
'@ ring: this mc
WDOG=ON
BASE(0,1)
UNITS=1: SPEED=50: ACCEL=500: DECEL=500
SERVO=ON: SERVO AXIS(1)=ON
start=TICKS
MOVE(30,40)             ' a path of 50 units
MOVE(-30,-40)           ' buffered behind it
WA(1)                   ' the next servo tick loads it into the axes' buffers
PRINT "NTYPE ";NTYPE[1,0];" (buffered)"
WAIT LOADED
PRINT "second move loaded after ";start-TICKS;" ms, at ";DPOS[5,1];",";DPOS AXIS(1)[5,1]
WAIT IDLE
WAIT IDLE AXIS(1)
PRINT "back at ";MPOS[4,1];",";MPOS AXIS(1)[4,1];" after ";start-TICKS;" ms"
