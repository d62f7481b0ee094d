# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The columns of the studies' tables (written by outputs.write_table: CSV, or Parquet by suffix).

CSV numbers are written with the fewest digits that read back to the same float64 (the
tolerance study's results are compared bit for bit). Parquet needs pyarrow (pip install -e
'.[study]').
"""

SENSITIVITY_COLUMNS = ('travel_mm', 'quantity', 'point', 'axis', 'derivative')
TOLERANCE_COLUMNS = ('travel_mm', 'quantity', 'nominal', 'mean', 'std', 'rss_std', 'p01', 'p99',
                     'out_of_reach')
