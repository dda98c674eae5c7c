"""``python -m shapelab COMMAND ...``: the command line (:mod:`shapelab.cli`)."""

import sys

from .cli import main

sys.exit(main())
