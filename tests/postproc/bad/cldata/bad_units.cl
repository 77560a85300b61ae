$$ expect: 2:7: error[E3116]: unknown units 'FEET'
UNITS/FEET
FINI
