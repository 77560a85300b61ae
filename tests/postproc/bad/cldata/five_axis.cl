$$ expect: 3:12: error[E3108]: tool axis (0.0000, 0.6000, 0.8000) is not +Z: a tilted tool (3+2) needs the CSYS of its frame first, and a tool axis that changes along the path (5-axis simultaneous) is not evaluated yet
GOTO/0,0,10
GOTO/1,2,3,0.0,0.6,0.8
FINI
