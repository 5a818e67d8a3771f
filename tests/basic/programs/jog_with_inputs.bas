' A jog station: while input 3 is on, the axis runs forward; when it goes off the move is
' cancelled and decelerates at DECEL. Input 7 ends the program.
'@ ring: this mc
'@ keys: wait=100 node1:in3=on wait=12500 node1:in3=off wait=12500 node1:in7=on
WDOG=ON
BASE(0): UNITS=1: SPEED=100: ACCEL=1000: DECEL=500: SERVO=ON
REPEAT
  WAIT UNTIL IN(3)=ON OR IN(7)=ON
  IF IN(3)=ON THEN
    FORWARD
    WAIT UNTIL IN(3)=OFF
    CANCEL
    WAIT IDLE
    PRINT "stopped at ";MPOS[7,2]
  ENDIF
UNTIL IN(7)=ON
PRINT "inputs ";IN(0,7)[4,0]
