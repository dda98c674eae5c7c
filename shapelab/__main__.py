"""``python -m shapelab COMMAND ...``: the command line (:mod:`shapelab.tools.cli`)."""

import sys

from .tools.cli import main

sys.exit(main())
