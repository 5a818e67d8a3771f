' An operator menu on a membrane keypad: 1 sets the speed, 2 the length; digits, '.'
' and Y enter a value; START runs. The keypad sends its keys back to this controller.
'@ ring: this keypad
'@ keys: wait=500 1:1 1:2 1:5 1:y 1:2 1:7 1:5 1:. 1:5 1:y 1:start
SEND(10,2,10)
PRINT #10,CHR(12);CHR(14);"1 SPEED  2 LENGTH"
running=FALSE
REPEAT
  GET #3,k
  ON k GOSUB set_speed, set_length
  IF k=20 THEN running=TRUE
UNTIL running
PRINT #10,CHR(12);"RUN ";VR(1)[4,0];" ";VR(2)[6,1];
PRINT "speed ";VR(1);" length ";VR(2)
STOP

set_speed:
  GOSUB read_number
  VR(1)=value
  PRINT #10,CURSOR(20);"SPEED ";value[4,0];"    ";
  RETURN

set_length:
  GOSUB read_number
  VR(2)=value
  PRINT #10,CURSOR(20);"LENGTH ";value[6,1];
  RETURN

read_number:
  value=0: scale=0
  REPEAT
    GET #3,d
    IF d<10 THEN
      IF scale=0 THEN value=value*10+d ELSE value=value+d*scale: scale=scale/10
    ELSEIF d=15 THEN
      scale=0.1
    ENDIF
  UNTIL d=13
  RETURN
