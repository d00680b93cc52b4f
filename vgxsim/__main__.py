"""``python -m vgxsim ...``: the same as the ``vgxsim`` command."""

import sys

from vgxsim.cli import main

sys.exit(main())
