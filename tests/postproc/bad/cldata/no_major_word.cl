$$ expect: 2:1: error[E3117]: record does not start with a major word: '#!/bin/sh'
#!/bin/sh
FINI
