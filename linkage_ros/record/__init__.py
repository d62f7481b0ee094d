"""Files of a run, imported only when asked for: MCAP (rosbag2 layout) and Rerun (.rrd)."""
