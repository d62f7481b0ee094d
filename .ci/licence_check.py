#!/usr/bin/env python3
# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Run ros_license_toolkit on a package checkout; its exit status (0 passed, else failed).

    python .ci/licence_check.py PATH [ros_license_toolkit options]

PATH: a git checkout of the package without build products (.ci/run clones the committed
tree: the toolkit scans every file under PATH, a virtual environment included).

The toolkit downloads two things into ~/.cache/ros_license_toolkit once: package.xml's XSD
(REP 149) from download.ros.org, and the SPDX licence list from spdx.org. Where a host cannot
be reached and nothing is cached (this project's machines and CI reach only the package
registries), the toolkit would end the run with a traceback. There, and only there, each is
replaced, saying so once on stderr:
- the XSD: package.xml is validated by catkin_pkg's parser (the one rosdep and colcon use:
  format, required tags, names, licences);
- the SPDX list: the SPDX identifiers of scancode's licence database (scancode is the
  toolkit's own scanner; its data follows the SPDX list), deprecated ones left out.
Every check of the toolkit runs as it is otherwise; nothing is written into its cache.

Which files a second licence covers: the toolkit wants a source-files attribute on each
<license> tag but one (REP 347, a proposal), which package format 3 does not have: catkin_pkg,
and so colcon and rosdep, refuse a package.xml with it (the toolkit's issue #85). The files are
declared instead in REUSE.toml, the REUSE specification's place for files without a header of
their own, and given to the toolkit from there: a <license> tag without source-files gets the
paths of REUSE.toml's annotations with its SPDX identifier. The tag of the licence REUSE.toml
does not name stays the package's main licence (every other file). The toolkit finds "every
other file" with a glob that skips hidden folders (.ci/), whose files would then count as
covered by no tag: here the glob includes them.
"""

import functools
import glob
import os
import sys
import tomllib

import requests
from ros_license_toolkit import license_tag
from ros_license_toolkit.license_checks import license_tag_is_spdx, license_text_exists_check
from ros_license_toolkit.license_checks.schema_check import SchemaCheck
from ros_license_toolkit.main import main

_download_validate = SchemaCheck.validate
_download_spdx = license_tag.is_license_name_in_spdx_list
_tag_init = license_tag.LicenseTag.__init__


def validate(check, package):
    """Validate package.xml against the XSD, else (host unreachable) by catkin_pkg."""
    try:
        return _download_validate(check, package)
    except requests.exceptions.ConnectionError:
        from catkin_pkg.package import InvalidPackage, parse_package
        print('licence_check: the package.xml XSD cannot be downloaded from download.ros.org '
              'here: package.xml validated by catkin_pkg instead', file=sys.stderr)
        try:
            parse_package(package.abspath).validate()
        except InvalidPackage as exc:
            return False, str(exc)
        return True, ''


@functools.cache
def scancode_spdx_ids() -> frozenset:
    """Return the SPDX identifiers of scancode's licence database, deprecated ones left out."""
    from licensedcode.models import load_licenses
    print('licence_check: the SPDX licence list cannot be downloaded from spdx.org here: '
          "scancode's copy of its identifiers used instead", file=sys.stderr)
    return frozenset(lic.spdx_license_key for lic in load_licenses().values()
                     if lic.spdx_license_key and not lic.is_deprecated
                     and not lic.spdx_license_key.startswith('LicenseRef-'))


def is_license_name_in_spdx_list(name: str) -> bool:
    """Say whether name is an SPDX licence identifier: spdx.org's list, else scancode's."""
    try:
        return _download_spdx(name)
    except requests.exceptions.ConnectionError:
        return name in scancode_spdx_ids()


def reuse_paths(package_path: str, spdx_id: str) -> list:
    """Return the path globs REUSE.toml gives the licence spdx_id in package_path, or []."""
    path = os.path.join(package_path, 'REUSE.toml')
    if not os.path.isfile(path):
        return []
    with open(path, 'rb') as stream:
        annotations = tomllib.load(stream).get('annotations', [])
    paths = []
    for annotation in annotations:
        if annotation.get('SPDX-License-Identifier') == spdx_id:
            listed = annotation.get('path', [])
            paths += [listed] if isinstance(listed, str) else listed
    return paths


def tag_init(tag, element, pkg_path, *args, **kwargs):
    """Read a <license> tag; one without source-files takes its files from REUSE.toml."""
    if 'source-files' not in element.attrib:
        paths = reuse_paths(pkg_path, str(element.text))
        if paths:
            element.attrib['source-files'] = ' '.join(paths)    # in memory only
    _tag_init(tag, element, pkg_path, *args, **kwargs)


def eval_glob(pattern: str, pkg_path: str) -> set:
    """Return the files pattern matches under pkg_path, relative to it, hidden ones included."""
    return {os.path.relpath(path, pkg_path)
            for path in glob.glob(os.path.join(pkg_path, pattern), recursive=True,
                                  include_hidden=True)
            if os.path.isfile(path) and '.git' not in path.split(os.sep)}


license_tag.LicenseTag.__init__ = tag_init
license_tag._eval_glob = eval_glob
SchemaCheck.validate = validate
for module in (license_tag, license_tag_is_spdx, license_text_exists_check):
    module.is_license_name_in_spdx_list = is_license_name_in_spdx_list

if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
