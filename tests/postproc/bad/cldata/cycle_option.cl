$$ expect: 2:13: error[E3112]: CYCLE/DRILL,DEEP is not expanded (peck, chip-break and other variants differ between CAM systems); post this operation with another post-processor
CYCLE/DRILL,DEEP,RAPTO,3.0000,FEDTO,0.0000,MMPM,250.0000
GOTO/66,0,240
CYCLE/OFF
FINI
