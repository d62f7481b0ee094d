# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The programs that write one text of a scene or vehicle: linkage-urdf and linkage-foxglove.

Both take SCENE_OR_VEHICLE (core.model.load_target: Target.prefixed gives the corners by the
node's TF frame prefix, '' for a scene, '<corner>/' for a vehicle's corner), -o FILE (stdout
for '-', else a file written whole) and --frame-id (run_text_program).
"""

from __future__ import annotations

import sys
from typing import Callable, TYPE_CHECKING

from .. import cli
from ..core.base import LinkageError
from ..core.model import load_target
from ..outputs import check_output, whole_file

if TYPE_CHECKING:
    from ..core.model import Target


class TextProgram:
    """What a text program says of itself: its name, doc, help texts, and how it makes the text."""

    def __init__(self, prog: str, doc: str, epilog: str, output_help: str, frame_help: str,
                 make: Callable[[Target, str], str], said: Callable[[Target, str], str]) -> None:
        """make(target, frame_id) -> the text; said(target, text) -> the line after writing."""
        self.prog, self.doc, self.epilog = prog, doc, epilog
        self.output_help, self.frame_help, self.make, self.said = (output_help, frame_help,
                                                                   make, said)

    def run(self, argv) -> int:
        """Parse argv, load the target, write its text; the exit status."""
        prog = self.prog
        parser = cli.Parser(prog, cli.summary(self.doc), self.epilog)
        parser.add_argument('target', metavar='SCENE_OR_VEHICLE',
                            help='bundled scene or vehicle name, or the path of either file')
        parser.add_argument('-o', '--output', metavar='FILE', required=True,
                            help=self.output_help)
        parser.add_argument('--frame-id', default='base_link', help=self.frame_help)
        args = parser.parse_args(argv)
        try:
            target = load_target(args.target)
            cli.warn(prog, target.warnings)
            check_text_output(args.output, target)
            text = self.make(target, args.frame_id)
            write_text(args.output, text)
        except (cli.Mistake, LinkageError) as exc:
            return cli.fail(prog, exc)
        if args.output != '-':
            print(f'{prog}: {target.name}: {self.said(target, text)} -> {args.output}',
                  file=sys.stderr)
        return cli.DONE


def check_text_output(output: str, target: Target) -> None:
    """Refuse -o FILE if it cannot be written or is a file the target was read from."""
    if output != '-':
        check_output(output, '-o', target.files)


def write_text(output: str, text: str) -> None:
    """Write text to stdout ('-') or whole to the file output."""
    if output == '-':
        sys.stdout.write(text)
        return
    with whole_file(output, encoding='utf-8') as stream:
        stream.write(text)
