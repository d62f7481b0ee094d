# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The package's import graph, read from its sources with ast.

No circle; every module of the package imports only from its own room and the rooms above it
in README's layout table (core's layers, cli, answer, record, chrono, ros, tools, study,
bench), and core's layers more strictly, each from the layers ALLOWED names.

Every import counts, also those under TYPE_CHECKING and those inside a function: a type or a
late import still ties two files together for a reader.
"""

import ast
from pathlib import Path
import re
import subprocess
import sys

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / 'linkage_ros'
README = PACKAGE.parent / 'README.md'
# each layer of core/ and the layers below it that it may import from
ALLOWED = {
    'base': {'base'},
    'model': {'base', 'model'},
    'solve': {'base', 'model', 'solve'},
    'measure': {'base', 'model', 'solve', 'measure'},
    'axle': {'base', 'model', 'solve', 'measure', 'axle'},
    'vehicle': {'base', 'model', 'solve', 'measure', 'axle', 'vehicle'},
    'statics': {'base', 'model', 'solve', 'measure', 'statics'},
    'vary': {'base', 'model', 'solve', 'measure', 'statics', 'vary'},
    'loads': {'base', 'model', 'solve', 'measure', 'axle', 'vehicle', 'statics', 'loads'},
}


def _module_name(path):
    parts = list(path.relative_to(PACKAGE.parent).with_suffix('').parts)
    return '.'.join(parts[:-1] if parts[-1] == '__init__' else parts)


def _resolve(name, package, node):
    """Return the absolute module that an ImportFrom names, relative or not."""
    if not node.level:
        return node.module
    base = package.split('.')
    base = base[:len(base) - node.level + 1]
    return '.'.join(base + ([node.module] if node.module else []))


def _face(path):
    """Return the names in a package's __all__ (its face), or an empty set."""
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], 'id', '') == '__all__':
            return {ast.literal_eval(e) for e in node.value.elts}
    return set()


def _graph():
    """Return {module: set of linkage_ros modules it imports} for every file of the package."""
    modules = {_module_name(p): p for p in PACKAGE.rglob('*.py')}
    faces = {name: _face(p) for name, p in modules.items() if p.name == '__init__.py'}
    graph = {}
    for name, path in modules.items():
        package = name if path.name == '__init__.py' else name.rpartition('.')[0]
        found = set()
        for node in ast.walk(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom):
                module = _resolve(node.module, package, node)
                # from package import submodule names a module, unless the package's face
                # gives that name (measure's alignment is the function alignment.alignment)
                targets = [f'{module}.{a.name}' if f'{module}.{a.name}' in modules
                           and a.name not in faces.get(module, ()) else module
                           for a in node.names]
            else:
                continue
            found.update(t for t in targets if t in modules and t != name)
        graph[name] = found
    return graph


GRAPH = _graph()


def _layer(module):
    parts = module.split('.')
    if parts[:2] != ['linkage_ros', 'core'] or len(parts) < 4:
        return None   # outside core, core's face or a module above the layers (warmup)
    return parts[2]


def _circles(graph):
    """Return the strongly connected components of more than one module (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def _rooms():
    """Return the rooms of README's layout table, in its order: 'core/base', ..., 'bench'."""
    return [name.rstrip('/').removesuffix('.py') for name in
            re.findall(r'^\| `linkage_ros/([\w/.]*)` \|', README.read_text(), re.MULTILINE)]


def _room(module, rooms):
    """Return the room of README's table that holds module (the longest that matches)."""
    path = module.split('.')[1:]
    found = [r for r in rooms if r.split('/') == path[:len(r.split('/'))]]
    return max(found, key=len) if found else None


def test_readme_s_layout_table_has_a_room_for_every_module_of_the_package():
    rooms = _rooms()
    assert len(rooms) == len(set(rooms)) >= 10
    assert sorted(m for m in GRAPH if m != 'linkage_ros' and _room(m, rooms) is None) == []


def test_every_module_imports_only_from_its_room_and_the_rooms_above_it_in_readme():
    rooms = _rooms()
    rank = {room: i for i, room in enumerate(rooms)}
    upward = sorted((m, t) for m, targets in GRAPH.items() if m != 'linkage_ros'
                    for t in targets if rank[_room(t, rooms)] > rank[_room(m, rooms)])
    assert upward == []


def test_the_graph_reads_the_core_layers_it_checks():
    layers = {_layer(m) for m in GRAPH} - {None}
    assert layers == set(ALLOWED)


def test_no_module_of_the_package_is_in_an_import_circle():
    assert _circles(GRAPH) == []


@pytest.mark.parametrize('layer', sorted(ALLOWED))
def test_a_core_layer_imports_only_from_itself_and_the_layers_below(layer):
    upward = sorted((m, t) for m, targets in GRAPH.items() if _layer(m) == layer
                    for t in targets
                    if t.startswith('linkage_ros.core') and _layer(t) not in ALLOWED[layer])
    assert upward == []


def test_core_imports_nothing_of_the_package_outside_core():
    outside = sorted((m, t) for m, targets in GRAPH.items() if m.startswith('linkage_ros.core')
                     for t in targets if not t.startswith('linkage_ros.core'))
    assert outside == []


def test_the_base_layer_imports_nothing_of_core_but_itself():
    imported = {t for m, targets in GRAPH.items() if _layer(m) == 'base' for t in targets}
    assert {_layer(t) for t in imported} <= {'base'}


def test_code_outside_core_imports_the_core_through_its_faces():
    deep = sorted((m, t) for m, targets in GRAPH.items()
                  if not m.startswith('linkage_ros.core')
                  for t in targets if t.startswith('linkage_ros.core') and t.count('.') > 2)
    assert deep == []


def test_importing_the_core_leaves_rclpy_mcap_and_rerun_out():
    code = ('import sys, linkage_ros.core, linkage_ros.core.axle, linkage_ros.core.measure; '
            'print(sorted(m for m in ("rclpy", "mcap", "rerun") if m in sys.modules))')
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == '[]'
