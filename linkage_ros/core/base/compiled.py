# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
How the numerical kernels are compiled: one decorator, one cache key.

    @jit                    numba's njit(cache=True, nogil=True, error_model='numpy'), its
                            on-disk cache keyed on source_digest()
    @bare                   the same without numba's reference counting, for kernels that
                            allocate nothing and return no array (the statics')
    @jitable                numba's register_jitable: a plain Python function that kernels
                            compile in (JITABLE: the files that define such functions)
    kernel_sources()        every file of core/ that holds compiled functions (a line that
                            starts with @jit, @bare or @jitable), sorted
    source_digest()         sha256 of those files (their paths under core/ and their bytes)

numba keys each compiled function's cache on its own file alone, yet a kernel compiles in the
functions it calls from other files (so3.py's rotations into every kernel, jacobian_kernel.py's
LU into three): after an edit of so3.py numba would load the stale machine code of every
kernel that inlined it. Here every kernel's cache is keyed on one digest of all the compiled
sources, so that an edit of any of them recompiles them all, and an edit elsewhere none.

The key is set by numba's own cache locators (where the cache lives: NUMBA_CACHE_DIR, else
__pycache__ beside the source, else the user's cache folder), each with its source stamp
replaced, put first in numba's list of locators for this package's files only. numba has no
public call for this (CacheImpl._locator_classes): test_kernel checks that every kernel of the
package gets one of these locators with the installed numba.
"""

from __future__ import annotations

import functools
import hashlib
import inspect
from pathlib import Path
import re

from numba import njit
from numba.core import caching
from numba.extending import register_jitable

CORE = Path(__file__).resolve().parents[1]
_COMPILED = re.compile(r'^\s*@(?:jit|bare|jitable)\b', re.MULTILINE)

jit = njit(cache=True, nogil=True, error_model='numpy')
# numba's reference counting (its private _nrt flag) off: for kernels that allocate nothing and
# return no array (numba refuses to return a new array without it). Its atomic counts on every
# array passed or named were a third of a statics command (core/statics: doc/benchmarks.md).
bare = njit(cache=True, nogil=True, error_model='numpy', _nrt=False)
JITABLE = set()   # the files of jitable functions, as they are defined


def jitable(function=None, **options):
    """
    Decorate a function that stays Python's and that kernels compile in (register_jitable).

    As @jitable or @jitable(inline='always'); its file is recorded in JITABLE (a kernel
    source: the one cache key covers it).
    """
    def wrap(fn):
        JITABLE.add(Path(inspect.getfile(fn)).resolve())
        return register_jitable(**options)(fn) if options else register_jitable(fn)
    return wrap(function) if function is not None else wrap


def kernel_sources(root: Path = CORE) -> tuple[Path, ...]:
    """Return every .py file under root (core/) with a compiled function, and this one, sorted."""
    this = root / Path(__file__).resolve().relative_to(CORE)
    return tuple(sorted({this.resolve()} | {
        path.resolve() for path in root.rglob('*.py')
        if _COMPILED.search(path.read_text(encoding='utf-8'))}))


def digest_of(paths, root: Path = CORE) -> str:
    """Return the sha256 (hex) of files: each one's path relative to root, then its bytes."""
    digest = hashlib.sha256()
    for path in paths:
        digest.update(str(Path(path).relative_to(root)).encode() + b'\0')
        digest.update(Path(path).read_bytes() + b'\0')
    return digest.hexdigest()


@functools.cache
def source_digest() -> str:
    """Return the one cache key of every kernel: digest_of(kernel_sources()), once a process."""
    return digest_of(kernel_sources())


class _KeyedOnAllSources:
    """A numba cache locator of this package's kernels: source_digest() is every one's stamp."""

    def get_source_stamp(self):
        return source_digest()

    @classmethod
    def from_function(cls, py_func, py_file):
        try:
            ours = Path(py_file).resolve().is_relative_to(CORE)
        except (OSError, ValueError):   # a placeholder such as '<ipython-input>'
            return None
        return super().from_function(py_func, py_file) if ours else None


def _numba(name: str):
    """Return numba.core.caching's name (public since numba 0.62, _name before)."""
    return getattr(caching, name, None) or getattr(caching, '_' + name)


LOCATORS = tuple(type(f'AllSources{base.__name__.lstrip("_")}', (_KeyedOnAllSources, base), {})
                 for base in map(_numba, ('UserProvidedCacheLocator', 'InTreeCacheLocator',
                                          'UserWideCacheLocator')))
_IMPL = _numba('CacheImpl')
if not any(issubclass(c, _KeyedOnAllSources) for c in _IMPL._locator_classes):
    _IMPL._locator_classes[:0] = LOCATORS
