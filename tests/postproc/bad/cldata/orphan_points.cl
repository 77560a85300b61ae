$$ expect: 4:3: error[E3107]: a line of coordinates must follow a GOTO record (or end the previous one with '$')
GOTO/1,2,3
FEDRAT/100
  4,5,6
FINI
