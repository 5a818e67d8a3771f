' A supervisor that must not stop on a bad reading: ON BASICERROR sends it to a handler
' that reports the line, counts the error and carries on with the next reading.
'@ ring: this mc
ON BASICERROR GOTO trouble
TABLE(0,4,2,0,8,-1)          ' five readings, one of them 0
i=0
next_reading:
  WHILE i<5
    r=TABLE(i)
    i=i+1
    ratio=100/r
    PRINT "reading ";r[2,0];": ";ratio[7,2];" %"
  WEND
  PRINT "errors: ";errors[1,0]
  STOP

trouble:
  errors=errors+1
  PRINT "error at line ";ERROR_LINE[2,0];", skipping reading ";i[1,0]
  GOTO next_reading
