"""Benchmarks and their references: the extended-precision reference, the peer solvers,
linkage-bench and linkage-node-bench."""
