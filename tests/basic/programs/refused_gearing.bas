' A real program's electronic gearing: CONNECT is a Trio BASIC motion command that the
' simulator does not model, so the program is refused at compile time, naming the word.
'@ ring: this mc
WDOG=ON
BASE(1): SERVO=ON
CONNECT(0.5,0) AXIS(1)
