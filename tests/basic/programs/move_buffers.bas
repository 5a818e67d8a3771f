' Two moves given one after the other: the first waits to start (NTYPE) until the next servo tick, and
' the second waits in the program for its place, then takes NTYPE while the first runs (MTYPE).
'@ ring: this mc
SPEED=100: ACCEL=1000: DECEL=1000
MOVE(10)
PRINT "issued: MTYPE=";MTYPE[2,0];" NTYPE=";NTYPE[2,0]
MOVEABS(50)
PRINT "both:   MTYPE=";MTYPE[2,0];" NTYPE=";NTYPE[2,0]
WAIT IDLE
PRINT "end ";DPOS[6,2];" MTYPE=";MTYPE[2,0];" NTYPE=";NTYPE[2,0]
