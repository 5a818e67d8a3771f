' Timeouts with TICKS: wait up to a second for input 5, then poll for it for up to half a
' second more.
'@ ring: this mc
'@ keys: wait=18750 node1:in5=on
TICKS=1000
WAIT UNTIL TICKS<0 OR IN(5)=ON
IF IN(5)=ON THEN PRINT "input 5 too early" ELSE PRINT "no input after ";1000-TICKS[5,0];" ms"
TICKS=500
REPEAT
  polls=polls+1
UNTIL TICKS<0 OR IN(5)=ON
PRINT "input 5 after ";500-TICKS[4,0];" ms more"
