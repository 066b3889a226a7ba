import sys

from voxfab.cli import main

sys.exit(main())
