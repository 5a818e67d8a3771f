' A filling machine's sequence as a state machine: an IF/ELSEIF chain chooses the step,
' ON ... GOTO jumps to the report for the state it ends in.
'@ ring: this mc
CONSTANT "waiting", 0       ' not "idle": IDLE is a Trio BASIC axis parameter
CONSTANT "filling", 1
CONSTANT "capping", 2
CONSTANT "done", 3
state=waiting
bottles=0
REPEAT
  IF state=waiting THEN
    state=filling
  ELSEIF state=filling THEN
    level=level+25
    IF level>=100 THEN state=capping
  ELSEIF state=capping THEN
    bottles=bottles+1: level=0
    IF bottles<2 THEN state=filling ELSE state=done
  ELSE
    PRINT "no such state"
  ENDIF
  steps=steps+1
UNTIL state=done
ON state GOTO s1, s2, s3
s1: PRINT "stuck filling": STOP
s2: PRINT "stuck capping": STOP
s3: PRINT bottles[1,0];" bottles in ";steps[2,0];" steps"
x=0.5+.25+1e1+$10+2.5E-1
PRINT "numbers ";x
