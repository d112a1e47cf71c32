"""``python -m contactsep``: the same as the ``contactsep`` command."""

import sys

from contactsep.cli import main

sys.exit(main())
