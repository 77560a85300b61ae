$$ expect: 2:8: error[E3103]: empty parameter where a number is expected
GOTO/1,,3
FINI
