# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Pictures of the studies (matplotlib, the plot extra): a tolerance stack-up, a fit.

plot_tolerance: per quantity, the Monte Carlo distribution of the deviation from the nominal
design at each travel (a violin), its 1st and 99th percentiles (ticks), and the first-order
band +-2.326 rss_std (where a normal distribution puts its 1st and 99th percentiles).
plot_fit: per target, the quantity over travel before and after the fit, and the target.
"""

from __future__ import annotations

import numpy as np

Z99 = 2.3263478740408408   # the 99th percentile of a standard normal distribution


def _pyplot():
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    return plt


def plot_tolerance(result, path: str, title: str) -> None:
    """Draw the distributions of a tolerance.Tolerance into path (PNG)."""
    plt = _pyplot()
    count = len(result.quantities)
    fig, axes = plt.subplots(count, 1, figsize=(9, 2.3 * count), sharex=True, squeeze=False)
    travel = result.travel
    width = 0.7 * (np.min(np.diff(np.unique(travel))) if len(np.unique(travel)) > 1 else 1.0)
    for q, (ax, name) in enumerate(zip(axes[:, 0], result.quantities)):
        deviation = result.values[:, :, q] - result.nominal[:, q]
        kept = [column[np.isfinite(column)] for column in deviation.T]
        drawn = [i for i, column in enumerate(kept) if len(column) > 1 and np.ptp(column) > 0]
        if drawn:
            parts = ax.violinplot([kept[i] for i in drawn], positions=travel[drawn],
                                  widths=width, showextrema=False)
            for body in parts['bodies']:
                body.set_alpha(0.6)
                body.set_zorder(2)
        band = Z99 * result.rss_std[:, q]
        ax.fill_between(travel, -band, band, color='tab:orange', alpha=0.12, zorder=0)
        ax.plot(travel, band, '--', color='tab:orange', lw=1,
                label='first order p01, p99 (+-2.326 rss_std)')
        ax.plot(travel, -band, '--', color='tab:orange', lw=1)
        ax.plot(travel, result.p01[:, q] - result.nominal[:, q], '_', color='k', ms=12)
        ax.plot(travel, result.p99[:, q] - result.nominal[:, q], '_', color='k', ms=12,
                label='Monte Carlo p01, p99')
        ax.axhline(0.0, color='grey', lw=0.5)
        ax.set_ylabel(f'{name}\n- nominal', fontsize=8)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=7, loc='upper right')
    axes[0, 0].set_title(title)
    axes[-1, 0].set_xlabel('travel, mm (+ = bump)')
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_fit(targets, result, path: str) -> None:
    """Draw each target's quantity before and after a fit.Fit into path (PNG)."""
    plt = _pyplot()
    count = len(targets.targets)
    fig, axes = plt.subplots(count, 1, figsize=(8, 3 * count), squeeze=False)
    for ax, t, before, after in zip(axes[:, 0], targets.targets, result.before.values,
                                    result.after.values):
        marker = 'o' if len(t.travel) == 1 else None    # a target at one travel: points
        ax.plot(t.travel, before, '--', color='tab:grey', marker=marker, mfc='none', ms=9,
                label='before')
        ax.plot(t.travel, after, '-', color='tab:blue', marker=marker, label='after')
        ax.plot(t.travel, t.value, 'o', ms=3, color='tab:red', label='target')
        ax.set_ylabel(t.quantity)
        ax.set_xlabel('travel, mm')
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[0, 0].set_title(f'{targets.design.scene.name}: fit of '
                         f'{", ".join(targets.names())}', fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
