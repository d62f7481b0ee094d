# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""Files of a run, imported only when asked for: MCAP (rosbag2 layout) and Rerun (.rrd)."""
