$$ expect: 2:1: error[E3114]: GODLTA before any FROM or GOTO: no position to move from
GODLTA/0,0,5
FINI
