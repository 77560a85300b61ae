$$ expect: 2:8: error[E3105]: unknown COOLNT word 'BLUE'
COOLNT/BLUE
FINI
