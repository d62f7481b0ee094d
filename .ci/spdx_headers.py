#!/usr/bin/env python3
# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0
"""
Give every source file of the package its SPDX header; safe to run again and again.

    python3 .ci/spdx_headers.py           add the header where it is missing, list those files
    python3 .ci/spdx_headers.py --check   change nothing; list the files without it, status 1

The header is the two comment lines of the REUSE specification (3.x) that
ros_license_toolkit's scanner (scancode) reads as the Apache-2.0 expression:

    # SPDX-FileCopyrightText: 2026 linkage_ros authors
    # SPDX-License-Identifier: Apache-2.0

A file has it when both tags are among its first HEAD_LINES lines (any holder on the
copyright tag: a file taken from elsewhere keeps its own notice too). A line that must stay
first (a shebang, then a PEP 263 encoding line) stays first; the header follows it, then a
blank line. Only the missing tag is added, so a second run changes nothing.

Source files: the Python files and shell scripts (a .sh, or a file starting with #!) that git
knows or would add (tracked, or untracked and not ignored) under ROOTS. Data (YAML scenes, the
test resources) carries no header: the package's licence covers it (package.xml).
"""

from __future__ import annotations

from pathlib import Path
import re
import subprocess
import sys

REPO = Path(__file__).resolve().parent.parent
ROOTS = ('linkage_ros', 'linkage_ros_pytest.py', 'test', '.ci', 'launch', 'setup.py')
COPYRIGHT = '# SPDX-FileCopyrightText: 2026 linkage_ros authors'
LICENSE = '# SPDX-License-Identifier: Apache-2.0'
# The tags as REUSE and scancode find them, in any comment form.
COPYRIGHT_TAG = re.compile(r'SPDX-FileCopyrightText:\s*\S')
LICENSE_TAG = re.compile(r'SPDX-License-Identifier:\s*Apache-2\.0\b')
HEAD_LINES = 10                  # the header is looked for at the top only
ENCODING = re.compile(r'^[ \t\f]*#.*?coding[:=][ \t]*[-\w.]+')    # PEP 263


def source_files(repo: Path = REPO) -> list[Path]:
    """Return the package's Python files and shell scripts under ROOTS, sorted."""
    try:
        listed = subprocess.run(
            ['git', '-C', str(repo), 'ls-files', '--cached', '--others', '--exclude-standard',
             '--', *ROOTS], check=True, capture_output=True, text=True).stdout.split('\n')
        paths = {repo / name for name in listed if name}
    except (OSError, subprocess.CalledProcessError):     # not a git checkout: walk the roots
        paths = {path for root in ROOTS for path in
                 ([repo / root] if (repo / root).is_file() else (repo / root).rglob('*'))
                 if '__pycache__' not in path.parts}
    return sorted(path for path in paths if path.is_file() and is_source(path))


def is_source(path: Path) -> bool:
    """Say whether path is a Python file or a shell script (by suffix or shebang)."""
    if path.suffix in ('.py', '.sh'):
        return True
    if path.suffix:
        return False
    with path.open('rb') as stream:
        return stream.read(2) == b'#!'


def missing(text: str) -> list[str]:
    """Return the header lines text lacks among its first HEAD_LINES lines, in header order."""
    head = '\n'.join(text.split('\n')[:HEAD_LINES])
    return [line for line, tag in ((COPYRIGHT, COPYRIGHT_TAG), (LICENSE, LICENSE_TAG))
            if not tag.search(head)]


def with_header(text: str) -> str:
    """Return text with the missing header lines after its shebang and encoding lines."""
    lines = missing(text)
    if not lines:
        return text
    body = text.split('\n')
    keep = 0                                   # lines that must stay first
    if body and body[0].startswith('#!'):
        keep = 1
    if len(body) > keep and keep < 2 and ENCODING.match(body[keep]):
        keep += 1
    rest = body[keep:]
    present = any(COPYRIGHT_TAG.search(line) or LICENSE_TAG.search(line)
                  for line in rest[:HEAD_LINES])
    # A half header: the missing tag goes beside the one there, with no blank line between.
    gap = [] if present or not rest or not rest[0].strip() else ['']
    return '\n'.join(body[:keep] + lines + gap + rest)


def main(argv: list[str] | None = None) -> int:
    """Add the header where missing (or with --check only list those files); see the module."""
    argv = sys.argv[1:] if argv is None else argv
    check = argv == ['--check']
    if argv and not check:
        print('usage: spdx_headers.py [--check]', file=sys.stderr)
        return 2
    files = source_files()
    lacking = [path for path in files if missing(path.read_text(encoding='utf-8'))]
    if check:
        for path in lacking:
            print(path.relative_to(REPO))
        if lacking:
            print(f'{len(lacking)} file(s) without the SPDX header: python3 '
                  '.ci/spdx_headers.py adds it', file=sys.stderr)
        return 1 if lacking else 0
    for path in lacking:
        path.write_text(with_header(path.read_text(encoding='utf-8')), encoding='utf-8')
        print(path.relative_to(REPO))
    return 0


if __name__ == '__main__':
    sys.exit(main())
