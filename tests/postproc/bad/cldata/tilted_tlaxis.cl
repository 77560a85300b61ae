$$ expect: 2:8: error[E3108]: tool axis (1.0000, 0.0000, 0.0000) is not +Z: multi-axis (or tilted 3+2) paths cannot be converted to 3-axis motion
TLAXIS/1,0,0
FINI
