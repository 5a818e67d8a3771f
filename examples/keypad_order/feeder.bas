' The feeder (node 2) writes on the keypad's second line and tells the master it is ready, at once: before
' the master has put the keypad into network mode. The keypad drops both messages (the manual's warning).
PRINT #10,CURSOR(20);"FEEDER READY";     ' to the keypad, the next node
PRINT #11,"R";                           ' to the master, two nodes on: through the keypad
