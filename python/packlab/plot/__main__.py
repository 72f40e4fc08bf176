import sys

from packlab.plot import main

sys.exit(main())
