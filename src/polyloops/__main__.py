import sys

from polyloops.cli import main

sys.exit(main())
