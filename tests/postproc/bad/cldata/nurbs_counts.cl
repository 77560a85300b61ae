$$ expect: 3:1: error[E3111]: 3 KNOT values and 1 CNTRL points do not make a B-spline of degree 1 to 9
GOTO/0,0,0
NURBS/
KNOT/0.3,0.6,1.0
CNTRL/1,1,0
GOTO/2,2,0
FINI
