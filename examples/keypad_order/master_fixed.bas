' The ring: master (node 1) -> feeder (node 2) -> keypad (node 3) -> master.
' As master.bas, and once the keypad is in network mode the master tells the feeder so (VR(10)=1 on the
' feeder), as the manual's Example 2 hands over with VR(200).
WA(10)                                   ' its own initialisation: 10 ms
SEND(11,2,10)                            ' keypad offset: the keypad's keys go one node on, to the master
PRINT #11,CHR(12);CHR(14);"MASTER READY";
SEND(10,1,10,1)                          ' handshake: the keypad is in network mode
GET #4,reply                             ' the feeder sends "R" when it is ready
PRINT #11,CURSOR(14);"RUN";
