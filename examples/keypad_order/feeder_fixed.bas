' The feeder (node 2) waits for the master's handshake before it sends anything to or through the keypad.
WAIT UNTIL VR(10)=1                      ' the master sets VR(10) once the keypad is in network mode
PRINT #10,CURSOR(20);"FEEDER READY";     ' to the keypad, the next node
PRINT #11,"R";                           ' to the master, two nodes on: through the keypad
