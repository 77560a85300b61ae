$$ expect: 2:12: error[E3112]: CYCLE/BORE,BACK (back boring, G87) is not posted: it needs the spindle oriented and the tool shifted, which the CL data do not give
CYCLE/BORE,BACK,FEDTO,10,MMPM,100,RAPTO,3
FINI
