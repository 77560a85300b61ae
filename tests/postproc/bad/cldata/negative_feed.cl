$$ expect: 2:1: error[E3104]: FEDRAT must be positive
FEDRAT/-5,MMPM
FINI
