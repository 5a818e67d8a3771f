' The slave of handshake_master.bas: waits for a job number, moves the length it was
' given, acknowledges with the job number.
WDOG=ON
BASE(0): UNITS=10: SPEED=100: ACCEL=1000: DECEL=1000: SERVO=ON
done=0
REPEAT
  WAIT UNTIL VR(101)<>done
  IF VR(101)>0 THEN
    MOVE(VR(100))
    WAIT IDLE
    done=VR(101)
    SEND(10,1,200,done)
  ENDIF
UNTIL VR(101)<0
PRINT "slave at ";MPOS
