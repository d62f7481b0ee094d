# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
The sinks of suspension_node: recorders and viewers that receive every input and output.

    check_outputs(params, inputs)        refuse an output that is an input file or the other
                                         output (LinkageError naming the parameter)
    recording_files(params)              {output parameter: the file it records into}: as
                                         given, or a numbered sibling (never truncate a
                                         recording this process wrote)
    recording_metadata(params, inputs)   what the MCAP stores of the run: the parameters that
                                         shaped it, and the text of every scene and vehicle file
    open_sinks(params, scenes, qos, metadata, say) -> the recorders the parameters turn on;
                                         their modules (mcap, rerun) are imported only then
    Sinks(sinks, on_failure, log_error)  hands each input and output to every sink; one that
                                         fails is dropped, closed and reported, the others go on

A sink is any object with record(topic, type_name, cdr_bytes, receive_ns, publish_ns) and
close(), and optionally error (why it stopped, set by a recorder that writes in the
background) and path.

The recording's custom_data (rosbag2 metadata, McapRecorder's custom_data) holds 'scene',
'vehicle', 'method', 'frame_id', 'max_step_mm' (as given). Its MCAP metadata record
'linkage_ros' (written first, so that a hard kill keeps it; read by linkage-replay and
linkage-rerun) holds the content of the files the run was solved from, so that it can be
solved again from any folder:
    'scene_yaml'             the scene file (a node of one scene)
    'vehicle_yaml'           the vehicle file (a vehicle node)
    'scene_yaml/<corner>'    each corner's scene file, as the vehicle file names it (unmirrored,
                             unplaced: the vehicle file says how)

A file a recorder of this process wrote is never opened again for writing (which would empty
it): the managed node's configure after a cleanup, say, with record_mcap still run.mcap,
records into run_1.mcap, the next into run_2.mcap, and says so on the log. Each file is a
whole recording of one configure (its own header, metadata, summary and footer), readable
alone, as rosbag2 splits a bag into numbered files; a finished MCAP is not reopened to
append, which would rewrite its summary and could lose it. A file written by an earlier
process is overwritten, as always.
"""

from __future__ import annotations

import contextlib
from pathlib import Path
import stat
from typing import Callable, TYPE_CHECKING

from ..cli import missing_package
from ..core.base import LinkageError
from ..outputs import output_problem, same_file

if TYPE_CHECKING:
    from rclpy.qos import QoSProfile

    from ..core.model import Scene

OUTPUTS = ('record_mcap', 'rerun_rrd')
# The regular files this process's recorders (open_sinks) wrote: their resolved paths and
# (st_dev, st_ino), so that a symbolic or hard link to one is known too.
RECORDED: set = set()
ABOUT = ('scene', 'vehicle', 'method', 'frame_id', 'max_step_mm')
STORED_RECORD = 'linkage_ros'   # the MCAP metadata record of the files' content


def check_outputs(params: dict, inputs: dict[str, str]) -> None:
    """
    Refuse outputs that cannot be written, that are an input, or that are both one file.

    params: the node's parameter values; inputs: {what: path} of the files the run reads
    ('scene file', 'vehicle file', ...). Paths are compared resolved (and by inode where
    both exist), so that ./run.mcap and $PWD/run.mcap are one file. Raises LinkageError naming
    the parameter, before anything is written.
    """
    outputs = recording_files(params)
    for name, path in outputs.items():
        problem = output_problem(path)
        if problem:
            raise LinkageError(name, problem)
        for what, other in inputs.items():
            if same_file(path, other):
                raise LinkageError(name, f'{path} is the {what}; give another file name')
    if len(outputs) == 2 and same_file(*outputs.values()):
        raise LinkageError('record_mcap', f'{params["record_mcap"]} is also rerun_rrd; give '
                           'each output its own file')


def recording_files(params: dict) -> dict[str, str]:
    """
    Return {output parameter: the file it records into} of the outputs turned on.

    That is the file the parameter names, unless this process recorded into it before (an
    earlier configure of the managed node): then the first of its numbered siblings,
    <stem>_1<suffix>, <stem>_2<suffix>, ..., that this process has not recorded into.
    """
    files = {}
    for name in OUTPUTS:
        if params[name]:
            path, number = Path(params[name]), 0
            while _recorded_here(path):
                number += 1
                path = Path(params[name]).with_name(
                    f'{Path(params[name]).stem}_{number}{Path(params[name]).suffix}')
            files[name] = str(path)
    return files


def _recorded_here(path: Path) -> bool:
    """Tell whether a recorder of this process wrote the file path names (RECORDED)."""
    if path.resolve() in RECORDED:
        return True
    try:
        status = path.stat()
    except OSError:
        return False
    return (status.st_dev, status.st_ino) in RECORDED


def _remember(path: str) -> None:
    """Add a file a recorder just claimed to RECORDED (regular files: not /dev/null)."""
    with contextlib.suppress(OSError):
        status = Path(path).stat()
        if stat.S_ISREG(status.st_mode):
            RECORDED.update({Path(path).resolve(), (status.st_dev, status.st_ino)})


def recording_metadata(params: dict, sources: dict[str, str]) -> dict[str, str]:
    """
    Return the custom_data of the run's recording (keys in the module docstring).

    sources: {custom_data key: path} of the files the run was solved from.
    """
    about = {name: str(params[name]) for name in ABOUT}
    for key, path in sources.items():
        about[key] = Path(path).read_text(encoding='utf-8', errors='replace')
    return about


@contextlib.contextmanager
def named(parameter: str):
    """Say which parameter a recorder that cannot start came from (/dev/full, say)."""
    try:
        yield
    except LinkageError as exc:
        raise LinkageError(parameter, str(exc)) from None


def open_sinks(params: dict, scenes: dict[str, Scene], qos: dict[str, QoSProfile],
               metadata: dict[str, str], say: Callable[[str], None]) -> list:
    """
    Open the sinks the parameters turn on; their modules are imported only then.

    scenes: {topic prefix: Scene} ('' for a node of one scene, 'front_left/' ...). qos:
    {topic: QoSProfile} the node offers, stored in the MCAP channel metadata; metadata: what
    recording_metadata gives. With a vehicle, the one Rerun recording draws every corner
    under its name. An output that cannot be written or a missing package raises
    LinkageError naming the parameter, before any command is taken. Each records into the
    file recording_files gives; say(line) tells where that is not the one the parameter
    names.
    """
    files = recording_files(params)
    for name, path in files.items():
        if path != params[name]:
            say(f'{name}: {params[name]} holds an earlier recording of this process, kept '
                f'whole; this one goes to {path}')
    sinks = []
    try:
        if params['record_mcap']:
            try:
                from ..record.mcap_writer import McapRecorder
            except ImportError as exc:
                raise LinkageError('record_mcap',
                                   missing_package(exc, 'recording to MCAP')) from None
            about = {k: v for k, v in metadata.items() if k in ABOUT}
            stored = {k: v for k, v in metadata.items() if k not in ABOUT}
            with named('record_mcap'):
                sinks.append(McapRecorder(files['record_mcap'], qos=qos, custom_data=about,
                                          metadata={STORED_RECORD: stored}))
            _remember(files['record_mcap'])
        if params['rerun_rrd']:
            try:
                from ..record.rerun_view import RerunRecorder
            except ImportError as exc:   # pyarrow comes with rerun-sdk: name the package
                raise LinkageError('rerun_rrd', missing_package(exc, 'mirroring to Rerun')) \
                    from None
            with named('rerun_rrd'):
                if '' in scenes:
                    sinks.append(RerunRecorder(files['rerun_rrd'], scenes['']))
                else:
                    sinks.append(RerunRecorder(files['rerun_rrd'], corners={
                        prefix.rstrip('/'): scene for prefix, scene in scenes.items()}))
            _remember(files['rerun_rrd'])
    except BaseException:
        for sink in sinks:
            sink.close()
        raise
    return sinks


class Sinks:
    """
    The sinks of a run, fed together.

    A sink whose record() raises, or whose error turns non-empty (check()), is dropped and
    closed, and on_failure(sink, reason) is called; the others go on. log_error(text) says
    that a sink failed to close.
    """

    def __init__(self, sinks: list, on_failure: Callable[[object, str], None],
                 log_error: Callable[[str], None]) -> None:
        self.active = list(sinks)
        self.on_failure, self.log_error = on_failure, log_error

    def __bool__(self) -> bool:
        return bool(self.active)

    def record(self, topic: str, type_name: str, data: bytes, receive_ns: int,
               publish_ns: int) -> None:
        """Hand one message (CDR bytes of type_name on topic) to every sink."""
        for sink in list(self.active):
            try:
                sink.record(topic, type_name, data, receive_ns, publish_ns)
            except Exception as exc:  # a broken recorder must not stop the node
                self._drop(sink, getattr(sink, 'error', None) or str(exc))

    def check(self) -> None:
        """Drop the sinks that failed in the background (a recorder's flushing thread)."""
        for sink in list(self.active):
            if getattr(sink, 'error', None):
                self._drop(sink, sink.error)

    def close(self) -> None:
        """Close every sink once (files are finished here); later calls do nothing."""
        sinks, self.active = self.active, []
        for sink in sinks:
            self._close(sink)

    def _drop(self, sink, reason):
        self.active.remove(sink)
        self._close(sink)
        self.on_failure(sink, reason)

    def _close(self, sink):
        try:
            sink.close()
        except Exception as exc:  # one failing sink must not keep the others open
            self.log_error(f'closing {type(sink).__name__}: {exc}')
