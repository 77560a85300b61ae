$$ expect: 2:8: error[E3102]: invalid byte 0xFF in a parameter
GOTO/1,ÿ2,3
FINI
