import sys

from fastrock.cli.app import main

sys.exit(main())
