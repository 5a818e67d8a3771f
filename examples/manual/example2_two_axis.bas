readinit:
  IF NOT(KEY#4) THEN GOTO readinit
  GET #4, VR(100)
  IF VR(100)<>73 THEN GOTO readinit
  GOSUB initax
  SEND(11,1,200,99)
readsp:
  IF NOT(KEY#4) THEN GOTO readsp
  SPEED=VR(1)
  GET#4,VR(100)
  IF VR(100)<>71 THEN GOTO readsp
  SEND(11,1,200,999)
moves: 'Main motion routine
  STOP ' placeholder body (not in the manual): the motion routine is left out, the program stops here
initax: 'Initialisation routine
  RETURN ' placeholder body (not in the manual): nothing to initialise
