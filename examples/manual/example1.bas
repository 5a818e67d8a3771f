length=2
' Set offset on first keypad to 2, i.e. send key press to MC
SEND(10,2,11)
' Set offset on second keypad to 1, i.e. send key press to MC
SEND(11,2,10)

' Clear first display & make cursor invisible
PRINT #10,CHR(12);CHR(14);CHR(20)
' Clear second display & make cursor invisible
PRINT #11,CHR(12);CHR(14);CHR(20)
' setup display
PRINT #10,"SPEED:":PRINT #10,"LENGTH:"
PRINT #11,"SPEED:":PRINT #11,"LENGTH:"

REPEAT
    IF KEY#3 THEN GOSUB read_key ELSE GOSUB do_motion
UNTIL FALSE
read_key:
GET #3,k
IF k>9 THEN GOTO not_num
a=a*10+k
IF a>9999 THEN a=0
PRINT #10,CHR(27);CHR(72);CHR(7);a[6,0]
PRINT #11,CHR(27);CHR(72);CHR(7);a[6,0]
not_num:
IF (k=10)&(VR(length)<10000) THEN VR(length)=VR(length)+0.1
IF (k=11)&(VR(length)>0.1) THEN VR(length)=VR(length)-0.1
PRINT #10,CURSOR(28);VR(length)[8,1]
PRINT #11,CURSOR(28);VR(length)[8,1]
RETURN

do_motion:
' Main motion routine
RETURN ' placeholder body (not in the manual): the motion routine is left out
