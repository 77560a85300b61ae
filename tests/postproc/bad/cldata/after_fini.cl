$$ expect: 4:1: warning[W3152]: records after FINI are ignored
GOTO/1,2,3
FINI
GOTO/4,5,6
