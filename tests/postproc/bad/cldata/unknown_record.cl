$$ expect: 2:1: error[E3118]: 'FROBNICATE' is not a record vcpost knows; it is refused rather than ignored, since it may move the tool or change the frame (record: FROBNICATE/1,2)
FROBNICATE/1,2
GOTO/1,2,3
FINI
