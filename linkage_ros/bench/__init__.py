"""
Benchmarks and their references.

The extended-precision reference, the peer solvers, linkage-bench and linkage-node-bench.
"""
