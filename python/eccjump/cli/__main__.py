"""``python -m eccjump.cli``: the same as the ``eccjump`` command."""

import sys

from eccjump.cli import main

sys.exit(main())
