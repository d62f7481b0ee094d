# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""python -m linkage_ros.bench.node_bench: the program, or a process it starts (--echo)."""

import sys

from .cli import main

sys.exit(main())
