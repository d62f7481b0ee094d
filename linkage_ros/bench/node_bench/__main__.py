"""python -m linkage_ros.bench.node_bench: the program, or a process it starts (--echo)."""

import sys

from .cli import main

sys.exit(main())
