# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Command-line programs: linkage-sweep, linkage-replay, linkage-rerun, the plots."""
