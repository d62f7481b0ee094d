# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The text output of linkage-urdf and linkage-foxglove: stdout ('-') or a file written whole.

Both take SCENE_OR_VEHICLE (core.model.load_target: Target.prefixed gives the corners by the
node's TF frame prefix, '' for a scene, '<corner>/' for a vehicle's corner) and -o FILE.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING

from ..outputs import check_output, whole_file

if TYPE_CHECKING:
    from ..core.model import Target


def check_text_output(output: str, target: Target) -> None:
    """Refuse -o FILE if it cannot be written or is a file the target was read from."""
    if output != '-':
        check_output(output, '-o', target.files)


def write_text(output: str, text: str) -> None:
    """Write text to stdout ('-') or whole to the file output."""
    if output == '-':
        sys.stdout.write(text)
        return
    with whole_file(output, encoding='utf-8') as stream:
        stream.write(text)
