' Two controllers share a job over the ring: the master hands each length to the slave
' (handshake_slave.bas) and waits for its acknowledgement, with a timeout from TICKS.
'@ ring: this mc:handshake_slave.bas
FOR job=1 TO 3
  SEND(10,1,100,job*10)        ' the length for the slave
  SEND(10,1,101,job)           ' then the job number: the slave starts on it
  TICKS=2000
  WAIT UNTIL VR(200)=job OR TICKS<0
  IF VR(200)<>job THEN
    PRINT "job ";job[1,0];" timed out"
    STOP
  ENDIF
  PRINT "job ";job[1,0];" done after ";2000-TICKS[4,0];" ms"
NEXT job
SEND(10,1,101,-1)              ' no more jobs
