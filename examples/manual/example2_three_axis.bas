init: SEND(11,2,10)'      Set offset on keypad
      PRINT #11,CHR(12);CHR(14);"INITIALISING....."
      PRINT #10,"I";'      Send command to two axis node to initialise
      GOSUB initax'      Initialisation routine
      WAIT UNTIL VR(200)=99'Two axis node signals ready by setting variable 200
      PRINT #11,CHR(12);CHR(14);"MACHINE READY"

      'Get required parameters
setlen:
      PRINT #11,"FEED LENGTH:";VR(0)[6.1];
      GET #3,VR(100)
      IF VR(100)=13 THEN GOTO setsp
      IF (VR(100)=10)AND(VR(0)<1000000) THEN VR(0)=VR(0)+0.1
      IF (VR(100)=11)AND(VR(0)>0.1) THEN VR(0)=VR(0)-0.1
      PRINT#11,CHR(27);CHR(72);CHR(32);VR(0)[6.1];
GOTO setlen
setsp:
      PRINT #11,"SPEED:";VR(1)[2];
      GET #3,VR(100)
      IF VR(100)=13 THEN GOTO initnet
      IF (VR(100)=10)AND(VR(1)<100) THEN VR(1)=VR(1)+0.01
      IF (VR(100)=11)AND(VR(1)>0.01) THEN VR(1)=VR(1)-0.01
      PRINT #11,CHR(27);CHR(72);CHR(46);VR(1)[2];
GOTO setsp

initnet:
      'Update variable values on two axis node
      SEND(10,1,0,VR(0))
      SEND(10,1,1,VR(1))

start:
      PRINT #11,CHR(12);CHR(14);"PRESS START TO RUN"
readkey:
  WAIT UNTIL KEY#3
  GET #3,VR(100)
  IF VR(100)<>20 THEN GOTO readkey
  PRINT #10,"G";
  WAIT UNTIL VR(200)=999
moves: 'Main motion routine
  STOP ' placeholder body (not in the manual): the motion routine is left out, the program stops here
initax: 'Initialisation routine
  RETURN ' placeholder body (not in the manual): nothing to initialise
