$$ expect: 3:1: error[E3110]: CIRCLE is not followed by a GOTO before the end of the file
GOTO/5,0,0
CIRCLE/0,0,0,0,0,1,5
FINI
