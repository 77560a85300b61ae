$$ expect: 3:1: error[E3106]: the file ends inside a record continued with '$'
GOTO/1,2,3
CIRCLE/0,0,0,$
