# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
Chrono::Vehicle suspension and vehicle JSON files, read and written (doc/chrono.md).

reader: the files as Chrono's RapidJSON reads them; templates: the named templates as data;
importer, parts, generic: a Chrono file -> a scene mapping; exporter: a scene -> a Chrono
object; writer: the texts; files: whole files in and out, checked (linkage-chrono's work).
"""

from .exporter import export_scene
from .files import export_file, import_file, inputs_of
from .importer import import_suspension, Imported
from .reader import ChronoError, parse_chrono, read_chrono
from .writer import json_text, scene_text

__all__ = ['ChronoError', 'export_file', 'export_scene', 'import_file', 'import_suspension',
           'Imported', 'inputs_of', 'json_text', 'parse_chrono', 'read_chrono', 'scene_text']
