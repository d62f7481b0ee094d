# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Every source file carries its SPDX header, and .ci/spdx_headers.py adds it idempotently.

The check and the header are the script's own (loaded from .ci/), so that what the test asks
for is what the script writes.
"""

import importlib.util
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parent.parent
SPEC = importlib.util.spec_from_file_location('spdx_headers', PACKAGE / '.ci' / 'spdx_headers.py')
spdx = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(spdx)
HEADER = [spdx.COPYRIGHT, spdx.LICENSE]


@pytest.mark.linter
def test_every_python_file_of_the_package_and_its_tests_has_the_spdx_header():
    files = spdx.source_files(PACKAGE)
    python = [path for path in files if path.suffix == '.py']
    assert len(python) > 100, 'the package and its tests were not found'
    for root in ('linkage_ros', 'test', '.ci'):
        assert any(path.is_relative_to(PACKAGE / root) for path in python), root
    lacking = [str(path.relative_to(PACKAGE)) for path in files
               if spdx.missing(path.read_text(encoding='utf-8'))]
    assert lacking == [], 'without the SPDX header (python3 .ci/spdx_headers.py adds it)'


@pytest.mark.linter
def test_the_licence_file_is_the_apache_2_0_text_package_xml_declares():
    text = (PACKAGE / 'LICENSE').read_text(encoding='utf-8')
    assert 'Apache License\n                           Version 2.0, January 2004' in text
    assert 'END OF TERMS AND CONDITIONS' in text
    assert '<license>Apache-2.0</license>' in (PACKAGE / 'package.xml').read_text()


def test_the_header_goes_after_a_shebang_and_an_encoding_line_then_a_blank_line():
    text = '#!/usr/bin/env python3\n# -*- coding: utf-8 -*-\n"""Doc."""\n'
    assert spdx.with_header(text).split('\n') == [
        '#!/usr/bin/env python3', '# -*- coding: utf-8 -*-', *HEADER, '', '"""Doc."""', '']


def test_the_header_goes_first_in_a_file_without_a_shebang():
    assert spdx.with_header('"""Doc."""\n').split('\n') == [*HEADER, '', '"""Doc."""', '']


def test_a_second_run_changes_nothing():
    for text in ('"""Doc."""\n', '#!/bin/bash\nset -e\n', '', 'x = 1'):
        once = spdx.with_header(text)
        assert spdx.with_header(once) == once
        assert spdx.missing(once) == []


def test_a_file_with_only_one_tag_gets_only_the_other():
    text = f'{spdx.LICENSE}\n"""Doc."""\n'
    assert spdx.with_header(text) == f'{spdx.COPYRIGHT}\n{text}'


def test_a_copyright_tag_of_another_holder_counts_as_the_copyright_line():
    text = '# SPDX-FileCopyrightText: 2017 Open Source Robotics Foundation, Inc.\n' \
        f'{spdx.LICENSE}\n'
    assert spdx.missing(text) == []


def test_a_header_below_the_first_lines_does_not_count():
    text = '\n' * spdx.HEAD_LINES + '\n'.join(HEADER) + '\n'
    assert spdx.missing(text) == HEADER


@pytest.mark.linter
def test_every_file_scanignore_names_exists():
    # ros_license_toolkit skips the files .scanignore names; a file moved without its line
    # there is scanned again, and CI's licence check fails on the licence it names
    names = [line.strip() for line in (PACKAGE / '.scanignore').read_text().splitlines()
             if line.strip() and not line.startswith('#')]
    assert [name for name in names if not (PACKAGE / name).exists()] == []
