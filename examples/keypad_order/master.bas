' The ring: master (node 1) -> feeder (node 2) -> keypad (node 3) -> master.
' The master owns the keypad: it sets the keypad's offset after its own initialisation, then waits for the
' feeder's "R".
WA(10)                                   ' its own initialisation: 10 ms
SEND(11,2,10)                            ' keypad offset: the keypad's keys go one node on, to the master
PRINT #11,CHR(12);CHR(14);"MASTER READY";
GET #4,reply                             ' the feeder sends "R" when it is ready
PRINT #11,CURSOR(14);"RUN";
