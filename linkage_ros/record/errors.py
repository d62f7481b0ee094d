# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The error of the recording modules: a file that cannot be written or read, a type unknown."""

from ..core.base import LinkageError


class RecordingError(LinkageError):
    """A recording cannot be written or read: RecordingError(file or type, problem)."""
