# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""The statics' compiled kernels, by module: for a benchmark that times their pieces apart."""

from . import command, forces, kernel, kkt, newton

__all__ = ['command', 'forces', 'kernel', 'kkt', 'newton']
