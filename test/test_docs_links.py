# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Every relative link of README.md and doc/*.md reaches a file, and its anchor a heading there.

Anchors are made as GitHub makes them from a heading: lower case, every character but letters,
digits, '_', '-' and spaces dropped, spaces turned to '-', a repeated one numbered -1, -2, ...
Links inside code (fenced blocks and `spans`) are not links and are not read.
"""

from pathlib import Path
import re

import pytest

ROOT = Path(__file__).resolve().parent.parent
PAGES = [ROOT / 'README.md', *sorted((ROOT / 'doc').glob('*.md'))]
LINK = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(([^()\s]+)\)')


def prose(text):
    """Yield the lines of a page outside fenced code."""
    fence = False
    for line in text.splitlines():
        if line.lstrip().startswith('```'):
            fence = not fence
        elif not fence:
            yield line


def slug(heading):
    """Return GitHub's anchor of a heading's text (before numbering repeats)."""
    text = re.sub(r'[`*_]{2,}|`', '', heading.strip()).lower()
    text = re.sub(r'\[([^\]]*)\]\([^)]*\)', r'\1', text)   # a link in a heading: its text
    return re.sub(r'[^\w\- ]', '', text).replace(' ', '-')


def anchors(page):
    """Return every anchor of a page's headings, repeats numbered as GitHub numbers them."""
    found, seen = set(), {}
    for line in prose(page.read_text()):
        match = re.match(r'#{1,6}\s+(.*?)\s*#*\s*$', line)
        if not match:
            continue
        base = slug(match.group(1))
        n = seen.get(base, 0)
        seen[base] = n + 1
        found.add(base if n == 0 else f'{base}-{n}')
    return found


def links(page):
    """Yield every relative link target of a page (no scheme, no mail)."""
    for line in prose(page.read_text()):
        for target in LINK.findall(re.sub(r'`[^`]*`', '``', line)):
            if not re.match(r'[a-z][a-z0-9+.-]*:', target):
                yield target


def test_slugs_are_made_as_github_makes_them():
    assert slug('The node: suspension_node') == 'the-node-suspension_node'
    assert slug('Elements (`linkage-map --benchmark`)') == 'elements-linkage-map---benchmark'
    assert slug("How the project's tests keep to themselves") == \
        'how-the-projects-tests-keep-to-themselves'


def test_a_link_to_a_missing_heading_is_found(tmp_path):
    page = tmp_path / 'page.md'
    page.write_text('# Top\n\n## Speed\n\n```\n# not a heading\n```\n[a](#speed) [b](#nope)\n'
                    '`[c](#in-code)`\n')
    assert anchors(page) == {'top', 'speed'}
    assert list(links(page)) == ['#speed', '#nope']


@pytest.mark.parametrize('page', PAGES, ids=lambda p: p.relative_to(ROOT).as_posix())
def test_every_relative_link_reaches_a_file_and_a_heading(page):
    broken = []
    for target in links(page):
        path, _, anchor = target.partition('#')
        where = (page.parent / path).resolve() if path else page
        if not where.exists():
            broken.append(f'{target}: no file {where.relative_to(ROOT)}')
        elif anchor and (where.suffix != '.md' or anchor not in anchors(where)):
            broken.append(f'{target}: no heading #{anchor} in {where.relative_to(ROOT)}')
    assert not broken, '\n'.join(broken)


def test_the_readme_links_every_page_of_the_manual():
    readme = set(links(ROOT / 'README.md'))
    assert [p.name for p in PAGES[1:] if f'doc/{p.name}' not in readme] == []


def test_the_readme_is_a_front_door_of_at_most_150_lines():
    # what it is, the two commands, an example, where the manual is (style guide, item 14);
    # the rest lives in doc/
    assert len((ROOT / 'README.md').read_text().splitlines()) <= 150
