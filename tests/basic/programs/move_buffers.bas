' Two moves given one after the other: each waits in the process (the manual's PMOVE) until the next servo
' tick loads it into the axis; the first starts there (MTYPE), the second waits in the program for its place,
' then shows in NTYPE from the tick after it was given while the first runs.
'@ ring: this mc
SPEED=100: ACCEL=1000: DECEL=1000
MOVE(10)
PRINT "issued: MTYPE=";MTYPE[2,0];" NTYPE=";NTYPE[2,0]
MOVEABS(50)
PRINT "both:   MTYPE=";MTYPE[2,0];" NTYPE=";NTYPE[2,0]
WA(1)
PRINT "loaded: MTYPE=";MTYPE[2,0];" NTYPE=";NTYPE[2,0]
WAIT IDLE
PRINT "end ";DPOS[6,2];" MTYPE=";MTYPE[2,0];" NTYPE=";NTYPE[2,0]
