' A cut-to-length line: feed a length of material, fire the knife, count the pieces
' until the batch is done. The batch size and the count live in VRs, named with GLOBAL.
'@ ring: this mc
CONSTANT "knife", 8
GLOBAL "batch", 10
GLOBAL "pieces", 11
batch=3

' drives on, axis 0 in mm (100 edges a mm)
WDOG=ON
BASE(0): UNITS=100: SPEED=200: ACCEL=2000: DECEL=2000: SERVO=ON
length=150

cycle_start=TICKS
WHILE pieces<batch
  MOVE(length)
  WAIT IDLE
  OP(knife,ON)
  WA(50)
  OP(knife,OFF)
  pieces=pieces+1
  PRINT "piece ";pieces[2,0];" at ";DPOS[8,1]
WEND
PRINT "batch of ";batch[1,0];" in ";(cycle_start-TICKS)/1000[6,3];" s"
