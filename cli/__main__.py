"""``python -m baranov.cli``."""

import sys

from .main import main

sys.exit(main())
