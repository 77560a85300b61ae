$$ expect: 2:1: error[E3113]: 'INDIRV' is an APT part-programming statement (geometry, not cutter locations); give the CAM system's CL output instead
INDIRV/ 0.0, 1.0, 0.0
TLON,GOFWD/ (CIRCLE/ 50.0, 30.0, 0.0, 20.0),ON,(LINE/ 50.0, 30.0, 0.0, 70.0, 30.0, 0.0)
FINI
