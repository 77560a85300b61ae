$$ expect: 3:1: warning[W3151]: the file ends without FINI or END-OF-PATH: it may be truncated
GOTO/1,2,3
GOTO/4,5,6
