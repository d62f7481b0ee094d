# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The bundled data (config/scenes, config/vehicles) and what a name given by a user means.

A bare name (no '/' and no suffix: five_link) is always a bundled file, whatever lies in the
current folder, so that a file there cannot stand in for a bundled scene unnoticed. Anything
else (five_link.yaml, ./five_link, /data/corner.yml) is a path. A bare name that is not
bundled but names a file here is refused with the path to give instead (./five_link).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from .yaml_file import SceneError

if TYPE_CHECKING:
    from os import PathLike

SOURCE_CONFIG = Path(__file__).resolve().parents[3] / 'config'   # in a source checkout


def config_dir() -> Path:
    """Return the package's config/ folder: the source tree's, or the installed share/ one."""
    if SOURCE_CONFIG.is_dir():
        return SOURCE_CONFIG
    try:
        from ament_index_python.packages import get_package_share_directory
        return Path(get_package_share_directory('linkage_ros')) / 'config'
    except Exception:  # not in an ament install: fall back to sys.prefix/share
        import sys
        return Path(sys.prefix) / 'share' / 'linkage_ros' / 'config'


def scene_dir() -> Path:
    """Return the folder of the bundled scenes."""
    return config_dir() / 'scenes'


def vehicle_dir() -> Path:
    """Return the folder of the bundled vehicle files."""
    return config_dir() / 'vehicles'


def bundled_scenes() -> list[str]:
    """Return the names of the scenes shipped in config/scenes."""
    return sorted(p.stem for p in scene_dir().glob('*.yaml'))


def is_bare_name(name_or_path: str | PathLike) -> bool:
    """Tell whether a name is bare (no '/', no suffix): a bundled file's name, not a path."""
    text = str(name_or_path)
    return '/' not in text and not Path(text).suffix and text not in ('.', '..')


def resolve(name_or_path: str | PathLike, kind: str = 'scene') -> Path:
    """
    Return the file a scene (kind='scene') or vehicle (kind='vehicle') name or path means.

    A bare name is looked up in the bundled folder only; a path is returned as given if it
    is a file, or has the suffix .yaml or .yml (the loader then says it cannot be read).
    Raises SceneError(name, kind, problem) for anything else, listing the bundled names.
    """
    folder = scene_dir() if kind == 'scene' else vehicle_dir()
    names = sorted(p.stem for p in folder.glob('*.yaml'))
    bundled = f'bundled: {", ".join(names)}'
    text = str(name_or_path)
    shown = text if kind == 'scene' and text.strip() else repr(text)
    if not text.strip():   # Path('') would be the current folder
        raise SceneError(shown, kind, f'empty: give a bundled {kind} name or the path of a '
                         f'{kind} YAML file ({bundled})')
    path = Path(text)
    try:
        return _resolved(path, text, shown, kind, folder, names, bundled)
    except OSError as exc:   # a name too long, a loop of links, no permission, ...
        raise SceneError(_shortened(shown), kind,
                         f'cannot be looked up ({exc.strerror or exc})') from None


def _shortened(text, most=200):
    """Return text cut to at most characters (a name of 5000 is said as its start)."""
    return text if len(text) <= most else f'{text[:most]}... ({len(text)} characters)'


def _resolved(path, text, shown, kind, folder, names, bundled):
    """resolve() once the name is not empty; OSError as the file system raises it."""
    if is_bare_name(text):
        if text in names:
            return folder / f'{text}.yaml'
        if path.is_file():
            raise SceneError(shown, kind, f'not a bundled {kind} ({bundled}); a bare name '
                             f'means a bundled {kind}: for the file {text} in this folder, '
                             f'give ./{text}')
        what = 'a folder' if path.is_dir() else 'no such file'
        raise SceneError(shown, kind, f'{what}, and not a bundled {kind} ({bundled})')
    if path.is_file() or path.suffix in ('.yaml', '.yml') and not path.is_dir():
        return path
    what = f'a folder, not a {kind} file' if path.is_dir() else 'no such file'
    raise SceneError(shown, kind, f'{what} ({bundled})')
