$$ expect: 2:7: error[E3112]: CYCLE/TAP is not expanded (only CYCLE/DRILL with FEDTO, RAPTO, RTRCTO, feed and DWELL is); post this operation with another post-processor
CYCLE/TAP,FEDTO,10,MMPR,1.5,RAPTO,3
FINI
