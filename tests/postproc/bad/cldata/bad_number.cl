$$ expect: 3:10: error[E3103]: malformed number '1.2.3'
GOTO/0,0,10
GOTO/1,2,1.2.3
FINI
