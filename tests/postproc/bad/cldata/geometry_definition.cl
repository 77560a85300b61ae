$$ expect: 2:1: error[E3113]: 'PT1' is an APT part-programming statement (geometry, not cutter locations); give the CAM system's CL output instead
PT1=POINT/1,2,3
FINI
