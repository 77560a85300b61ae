$$ expect: 2:1: error[E3104]: FEDRAT needs a feed value
FEDRAT/MMPM
FINI
