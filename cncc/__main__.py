import sys

from cncc.cli import main

sys.exit(main())
