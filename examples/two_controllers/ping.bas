' ping.bas: sends 1 to 5 in turn to the next controller's VR(20), waiting each time until it comes back in VR(21)
FOR n=1 TO 5
  SEND(10,1,20,n)
  WAIT UNTIL VR(21)=n
NEXT n
PRINT "all ";n-1[1,0];" came back"
