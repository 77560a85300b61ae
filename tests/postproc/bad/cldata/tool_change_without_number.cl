$$ expect: 5:1: error[E3120]: TLDATA/MILL,10,5,50,0,0 is another tool than the one cutting, but no LOAD/TOOL, LOADTL, TOOLNO or SELECT/TOOL gives its number: the tool change cannot be written (give the tool numbers in the CAM system)
TOOL PATH/FLAT,TOOL,FLAT_10
TLDATA/MILL,10,0,50,0,0
GOTO/0,0,10
TLDATA/MILL,10,5,50,0,0
GOTO/0,0,20
FINI
