$$ expect: 3:1: error[E3122]: CUTTER: diameter -10 mm is no milling tool's size (give a diameter above 0 and up to 5000 mm)
TOOL PATH/BALL,TOOL,BALL_10
CUTTER/-10,5
FEDRAT/500
GOTO/0,0,10
GOTO/10,0,0
FINI
