$$ expect: 3:12: error[E3108]: tool axis (0.0000, 0.6000, 0.8000) is not +Z: multi-axis (or tilted 3+2) paths cannot be converted to 3-axis motion
GOTO/0,0,10
GOTO/1,2,3,0.0,0.6,0.8
FINI
