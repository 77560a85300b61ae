$$ expect: 2:1: warning[W3150]: unknown record 'FROBNICATE' ignored (reported once)
FROBNICATE/1,2
GOTO/1,2,3
FINI
