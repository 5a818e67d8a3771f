' pong.bas: sends back to the next controller, in its VR(21), every new value that arrives in VR(20)
REPEAT
  WAIT UNTIL VR(20)<>VR(21)
  VR(21)=VR(20)
  SEND(10,1,21,VR(21))
UNTIL VR(21)=5
