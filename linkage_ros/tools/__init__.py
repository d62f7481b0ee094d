"""Command-line programs: linkage-sweep, linkage-replay, linkage-rerun, the plots."""
