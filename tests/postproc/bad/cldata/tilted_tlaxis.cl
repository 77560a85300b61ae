$$ expect: 2:8: error[E3108]: tool axis (1.0000, 0.0000, 0.0000) is not +Z: a tilted tool (3+2) needs the CSYS of its frame first, and a tool axis that changes along the path (5-axis simultaneous) is not evaluated yet
TLAXIS/1,0,0
FINI
