' Builds a motion profile in TABLE (a quarter sine in 11 points, 0 to 90 degrees), checks
' it and reports it, as a controller does before it runs a cam.
'@ ring: this mc
CONSTANT "points", 11
FOR i=0 TO points-1
  TABLE(i, 100*SIN(i*PI/20))
NEXT i
total=0
FOR i=0 TO points-1
  total=total+TABLE(i)
NEXT i
PRINT "first ";TABLE(0)[6,2];" middle ";TABLE(5)[6,2];" last ";TABLE(10)[6,2]
PRINT "mean ";total/points[8,4]
mask=0
FOR i=0 TO points-1
  IF TABLE(i)>50 THEN mask=mask OR 2^i
NEXT i
PRINT "over 50: $";HEX(mask)
PRINT "check: ";ATAN2(1,1)*4=PI;" ";SQR(2)^2;" ";EXP(LN(10))[6,3]
