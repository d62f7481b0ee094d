# SPDX-FileCopyrightText: 2026 linkage_ros authors
# SPDX-License-Identifier: Apache-2.0

"""
linkage-replay and linkage-rerun: --help, exit statuses, one line for each user mistake.

Statuses: 0 done with a complete input, 1 done with a damaged input, 2 a user mistake told in
one line on stderr that starts with the program's name (never a traceback).
"""

from pathlib import Path
import re
import subprocess
import sys

from linkage_ros.record.mcap_writer import McapRecorder
from linkage_ros.tools import replay, rerun_convert
from mcap.reader import make_reader
import pytest
from std_msgs.msg import Float64

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / 'bags' / 'five_link_sweep.mcap'
PROGRAMS = {'linkage-replay': replay.main, 'linkage-rerun': rerun_convert.main}


def one_line(capsys, prog):
    """Return the one line a mistake printed on stderr (asserted one, prefixed)."""
    captured = capsys.readouterr()
    assert captured.err.count('\n') == 1 and captured.err.endswith('\n'), captured.err
    assert captured.err.startswith(f'{prog}: '), captured.err
    assert 'Traceback' not in captured.err
    return captured.err[:-1]


def status_of(main, argv):
    """main(argv)'s exit status, whether returned or raised by argparse."""
    try:
        return main(argv)
    except SystemExit as exited:
        return exited.code


@pytest.fixture
def foreign_bag(tmp_path):
    """Write a complete bag without any topic linkage-rerun draws or linkage-replay solves."""
    path = tmp_path / 'other.mcap'
    with McapRecorder(path, flush_period=0) as rec:
        rec.record('/speed', 'std_msgs/msg/Float64', Float64(data=1.0), 5, 5)
    return path


# --- --help --------------------------------------------------------------------------------

STATUSES = ('0  done; the input was complete', '1  done, but the input was damaged',
            '2  a mistake in the command')


def help_of(main, argv, capsys):
    """Return the text main(argv) prints on stdout, asserting status 0."""
    assert status_of(main, argv) == 0
    return capsys.readouterr().out


def test_rerun_help_says_what_it_does_every_option_default_an_example_and_the_statuses(capsys):
    text = help_of(rerun_convert.main, ['--help'], capsys)
    assert text.startswith('usage: linkage-rerun ')
    assert 'linkage-rerun: convert a recorded run' in text
    assert all(status in text for status in STATUSES)
    assert '  linkage-rerun run.mcap' in text                      # an example
    assert "BAG's name" in text and 'in the current folder' in text   # the default output


def test_replay_help_names_each_subcommand_with_examples_and_the_statuses(capsys):
    text = help_of(replay.main, ['--help'], capsys)
    assert text.startswith('usage: linkage-replay ')
    assert 'linkage-replay: solve the wheel-travel' in text
    assert all(status in text for status in STATUSES)
    for command in ('solve', 'sweep', 'copy', 'publish'):
        assert f'\n    {command} ' in text                          # listed with its summary
        assert f'\n  linkage-replay {command} ' in text             # and an example


def test_replay_help_names_every_topic_a_solved_run_holds_with_its_type(capsys, tmp_path):
    # issue 27 item 25: the help left out elements, which a scene with elements adds
    from linkage_ros.record.mcap_reader import read_bag
    out = tmp_path / 'sweep.mcap'
    assert replay.main(['sweep', '--scene', 'double_wishbone', '--travel', '0:10:10',
                        '-o', str(out)]) == 0
    topics = read_bag(out).topics
    assert '/elements' in topics
    capsys.readouterr()
    text = ' '.join(help_of(replay.main, ['--help'], capsys).split())
    for topic, type_name in topics.items():
        if topic == '/wheel_travel':          # the commands: named with --topic
            continue
        assert re.search(rf'(^|[ /]){topic[1:]}\b', text), topic
        assert type_name.replace('/msg/', '/') in text, type_name


# subcommand: (its options, what its help says of units and defaults)
SUBCOMMAND_HELP = {
    'solve': (('--topic', '--scene', '--method', '--frame-id', '-o'),
              ('std_msgs/msg/Float64 in m (default /wheel_travel)',
               'the scene the recording stores, else five_link', '(default fast)',
               '(default base_link)', "BAG's name + _solved.mcap, in the current folder")),
    'sweep': (('--scene', '--travel', '--hz', '-o'),
              ('(default five_link)', 'travels, mm: FROM:TO:STEP (TO included) or one value',
               "(default: the scene's travel block)", 'rate, Hz, > 0 (default 50)',
               "the scene's name (its letters, digits, _ . -) + _sweep.mcap, in the current "
               'folder')),
    'copy': (('-o',), ("BAG's name + _copy.mcap, in the current folder",)),
    'publish': (('--topic', '--rate', '--clock', '--wait', '--travel', '--hz'),
                ('> 0 (default 1;', 's to wait for a subscriber, >= 0 (default 10)',
                 'without it, the commands of a sweep', 'sweep: travels, mm')),
}


@pytest.mark.parametrize('command', sorted(SUBCOMMAND_HELP))
def test_replay_subcommand_help_gives_every_option_default_and_unit_examples_and_statuses(
        command, capsys):
    text = help_of(replay.main, [command, '--help'], capsys)
    assert text.startswith(f'usage: linkage-replay {command} ')
    assert all(status in text for status in STATUSES)
    assert f'\n  linkage-replay {command} ' in text                 # an example
    options, phrases = SUBCOMMAND_HELP[command]
    for option in options:
        assert f'\n  {option} ' in text, option
    for phrase in phrases:
        assert phrase in ' '.join(text.split()), phrase


# --- statuses 0 and 1 ----------------------------------------------------------------------

def test_a_complete_bag_gives_status_0_and_a_damaged_one_status_1(tmp_path):
    assert replay.main(['solve', str(EXAMPLE), '-o', str(tmp_path / 'a.mcap')]) == 0
    assert replay.main(['copy', str(EXAMPLE), '-o', str(tmp_path / 'b.mcap')]) == 0
    assert rerun_convert.main([str(EXAMPLE), '-o', str(tmp_path / 'a.rrd')]) == 0
    cut = tmp_path / 'cut.mcap'
    cut.write_bytes(EXAMPLE.read_bytes()[:-100])
    assert replay.main(['solve', str(cut), '-o', str(tmp_path / 'c.mcap')]) == 1
    assert replay.main(['copy', str(cut), '-o', str(tmp_path / 'd.mcap')]) == 1
    assert rerun_convert.main([str(cut), '-o', str(tmp_path / 'b.rrd')]) == 1


def test_default_outputs_go_to_the_current_folder(tmp_path, monkeypatch):
    work = tmp_path / 'work'
    work.mkdir()
    monkeypatch.chdir(work)
    assert replay.main(['solve', str(EXAMPLE)]) == 0
    assert replay.main(['copy', str(EXAMPLE)]) == 0
    assert replay.main(['sweep', '--travel', '0:2:1']) == 0
    assert rerun_convert.main([str(EXAMPLE)]) == 0
    assert sorted(p.name for p in work.iterdir()) == [
        'five_link_sweep.mcap', 'five_link_sweep.rrd', 'five_link_sweep_copy.mcap',
        'five_link_sweep_solved.mcap']
    with open(work / 'five_link_sweep.mcap', 'rb') as stream:     # the sweep: 3 commands
        assert make_reader(stream).get_summary().statistics.channel_message_counts
    assert sorted(p.name for p in EXAMPLE.parent.iterdir() if p.suffix in ('.mcap', '.rrd')) \
        == ['five_link_sweep.mcap']


# --- status 2: one line each ---------------------------------------------------------------

def replay_mistakes(tmp_path, foreign_bag):
    """(argv, the line's expected end) of linkage-replay mistakes, in the subcommand spelling."""
    out = str(tmp_path / 'out.mcap')
    folder = tmp_path / 'empty_folder'
    folder.mkdir()
    blocker = tmp_path / 'a_file'
    blocker.write_text('')
    bag = str(EXAMPLE)
    missing = tmp_path / 'missing'
    return [
        (['--bogus'], 'error: unrecognized arguments: --bogus (see linkage-replay --help)'),
        ([], 'error: choose what to do: solve, sweep, copy, publish (see linkage-replay --help)'),
        (['solve'], 'error: the following arguments are required: BAG (see linkage-replay '
         'solve --help)'),
        (['sweep', bag], f'error: a sweep takes no BAG (unrecognized arguments: {bag})'),
        (['solve', str(tmp_path / 'none.mcap')], f'BAG {tmp_path / "none.mcap"}: no such file '
         'or folder'),
        (['solve', str(folder), '-o', out], f'{folder}: a bag folder must hold exactly one '
         '.mcap file (found: none)'),
        (['publish', bag, '--rate', '0'], 'error: argument --rate: must be a finite number '
         'above 0, got 0 (see linkage-replay publish --help)'),
        (['publish', bag, '--rate', 'nan'], 'argument --rate: must be a finite number above '
         '0, got nan'),
        (['publish', bag, '--rate', 'fast'], "argument --rate: expected a number, got 'fast'"),
        (['publish', bag, '--wait', '-1'], 'argument --wait: must be a finite number at '
         'least 0, got -1'),
        (['sweep', '--hz', '0'], 'argument --hz: must be a finite number above 0, got 0'),
        (['sweep', '--travel', '0:1:-1'], 'argument --travel: expected FROM[:TO:STEP], finite '
         "numbers with STEP > 0, got '0:1:-1'"),
        (['sweep', '--travel', 'inf'], 'argument --travel: expected FROM[:TO:STEP], finite '
         "numbers with STEP > 0, got 'inf'"),
        (['sweep', '--travel', '-80mm'], "argument --travel: '-80mm': give FROM[:TO:STEP] as "
         'plain numbers, without a unit'),
        (['solve', bag, '--rate', '2'], 'error: --rate is not an option of linkage-replay solve '
         '(it is one of: publish) (see linkage-replay solve --help)'),
        (['sweep', '--clock'], 'error: --clock is not an option of linkage-replay sweep (it is '
         'one of: publish)'),
        (['solve', bag, '--travel', '3'], 'error: --travel is not an option of linkage-replay '
         'solve '
         '(it is one of: sweep, publish)'),
        (['publish', bag, '--hz', '3'], 'error: --hz makes a sweep: give it without BAG'),
        (['publish', bag, '--scene', 'macpherson'], 'error: --scene makes a sweep: give it '
         'without BAG'),
        (['copy', bag, '--scene', 'macpherson'], 'error: --scene is not an option of '
         'linkage-replay copy'),
        (['publish', bag, '--method', 'paper'], 'error: --method is not an option of '
         'linkage-replay publish (it is one of: solve, sweep)'),
        (['publish', bag, '-o', out], 'error: -o is not an option of linkage-replay publish'),
        (['solve', bag, '--method', 'quick'], 'error: argument --method: invalid choice: '
         "'quick'"),
        (['solve', bag, '--scene', 'nowhere'], 'nowhere: scene: no such file, and not a bundled '
         'scene'),
        (['solve', bag, '-o', str(missing / 'out.mcap')], f'-o: cannot write '
         f'{missing / "out.mcap"}: no folder {missing}'),
        (['solve', bag, '-o', str(folder)], f'-o: {folder} is a folder, not a file'),
        (['solve', bag, '-o', str(blocker / 'out.mcap')], f'-o: cannot write '
         f'{blocker / "out.mcap"}: {blocker} is not a folder'),
        (['copy', bag, '-o', bag], f'-o: {bag} is the input {bag}; give another file name'),
        (['solve', bag, '-o', '/sys/out.mcap'], '-o: cannot write /sys/out.mcap: Permission '
         'denied'),
        (['solve', bag, '--topic', '/camber_x'], 'no topic /camber_x (topics present: '),
        (['solve', str(foreign_bag), '-o', out], f'{foreign_bag}: no topic /wheel_travel '
         '(topics present: /speed (std_msgs/msg/Float64)); choose the wheel-travel topic with '
         '--topic'),
    ]


def test_every_replay_mistake_is_one_line_and_status_2_and_writes_nothing(
        tmp_path, capsys, foreign_bag):
    for argv, expected in replay_mistakes(tmp_path, foreign_bag):
        assert status_of(replay.main, argv) == 2, argv
        line = one_line(capsys, 'linkage-replay')
        assert expected in line, (argv, line)
        assert not (tmp_path / 'out.mcap').exists()


@pytest.mark.parametrize('argv, expected', [
    (['--travel', '0:1:0.5 mm'], "argument --travel: '0:1:0.5 mm': give FROM[:TO:STEP] as "
     'plain numbers, without a unit (see linkage-bench replay --help)'),
    ([str(EXAMPLE), '--travel', '3'], 'error: --travel makes a sweep: give it without BAG'),
    ([str(EXAMPLE), '-o', 'out.mcap'], 'error: unrecognized arguments: -o out.mcap'),
    (['bench', str(EXAMPLE)], 'error: unrecognized arguments: ' + str(EXAMPLE)),   # 0.1.0's
    (['--scene', 'nowhere'], 'nowhere: scene: no such file, and not a bundled scene'),
    (['none.mcap'], 'BAG none.mcap: no such file or folder'),
])
def test_every_linkage_bench_replay_mistake_is_one_line_and_status_2(
        argv, expected, tmp_path, capsys, monkeypatch):
    from linkage_ros.bench.replay import main
    monkeypatch.chdir(tmp_path)
    assert status_of(main, argv) == 2, argv
    line = one_line(capsys, 'linkage-bench replay')
    assert expected in line, (argv, line)
    assert list(tmp_path.iterdir()) == []


def test_every_rerun_mistake_is_one_line_and_status_2_and_writes_nothing(
        tmp_path, capsys, foreign_bag):
    out = str(tmp_path / 'out.rrd')
    named = tmp_path / 'named.mcap'
    with McapRecorder(named, custom_data={'scene': 'gone_scene'}, flush_period=0) as rec:
        rec.record('/camber', 'std_msgs/msg/Float64', Float64(data=0.1), 5, 5)
    mistakes = [
        ([], 'error: the following arguments are required: BAG'),
        ([str(EXAMPLE), '--bogus'], 'error: unrecognized arguments: --bogus'),
        ([str(tmp_path / 'none.mcap')], f'BAG {tmp_path / "none.mcap"}: no such file or '
         'folder'),
        ([str(EXAMPLE), '-o', str(tmp_path / 'missing' / 'x.rrd')], f'no folder '
         f'{tmp_path / "missing"}'),
        ([str(EXAMPLE), '-o', str(tmp_path)], f'-o: {tmp_path} is a folder, not a file'),
        ([str(EXAMPLE), '-o', '/sys/out.rrd'], '-o: cannot write /sys/out.rrd: Permission '
         'denied'),
        ([str(EXAMPLE), '-o', str(EXAMPLE)], f'is the input {EXAMPLE}'),
        ([str(EXAMPLE), '--scene', 'nowhere', '-o', out], 'nowhere: scene: no such file'),
        ([str(named), '-o', out], 'gone_scene: scene: no such file, and not a bundled scene '
         '(bundled: '),
        ([str(foreign_bag), '-o', out], f'{foreign_bag}: no wheel_travel, steering_rack, '
         'wheel_carrier_pose, camber, toe, contact_wrench or pickup/<name> messages to '
         'convert (topics: /speed)'),
    ]
    for argv, expected in mistakes:
        assert status_of(rerun_convert.main, argv) == 2, argv
        line = one_line(capsys, 'linkage-rerun')
        assert expected in line, (argv, line)
        assert not (tmp_path / 'out.rrd').exists()
    assert status_of(rerun_convert.main, [str(named), '-o', out]) == 2
    assert capsys.readouterr().err.endswith('(the scene the bag names; choose one with '
                                            '--scene)\n')


@pytest.mark.parametrize('module, argv, expected', [
    ('mcap', ['linkage_ros.tools.replay', 'copy', str(EXAMPLE)],
     'linkage-replay: reading and writing bags needs the Python package mcap, which is not '
     "installed: pip install -e '.[record]' (in a linkage_ros checkout) or pip install mcap"),
    ('rclpy', ['linkage_ros.tools.replay', 'publish', str(EXAMPLE)],
     'linkage-replay: publishing on ROS 2 needs the Python package ros-jazzy-rclpy, which is '
     "not installed: pip install -e '.[ros]'"),
    ('rerun', ['linkage_ros.tools.rerun_convert', str(EXAMPLE)],
     'linkage-rerun: writing .rrd files needs the Python package rerun-sdk, which is not '
     "installed: pip install -e '.[view]' (in a linkage_ros checkout) or pip install "
     'rerun-sdk'),
    ('mcap', ['linkage_ros.tools.rerun_convert', str(EXAMPLE)],
     'linkage-rerun: reading bags needs the Python package mcap, which is not installed: '
     "pip install -e '.[record]'"),
])
def test_a_missing_optional_package_is_named_with_the_command_that_installs_it(
        tmp_path, module, argv, expected):
    # A fresh interpreter in which importing the package fails, as where it is not installed.
    code = (f'import runpy, sys; sys.modules[{module!r}] = None; sys.argv = {argv!r}; '
            f'runpy.run_module({argv[0]!r}, run_name="__main__")')
    result = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True,
                            timeout=120, cwd=tmp_path)
    assert result.returncode == 2, result.stderr
    assert result.stderr.count('\n') == 1 and result.stderr.startswith(expected), result.stderr
    assert list(tmp_path.iterdir()) == []


def test_study_workers_default_is_the_same_in_help_and_doc_study_md(capsys):
    # issue 27 item 25: --help said "every core", doc/study.md "every core once a study has
    # 16 batches"; both now say what linkage_ros.study.commands does, from its numbers.
    from linkage_ros.study import cli as study_cli
    from linkage_ros.study.commands import POOL_FROM
    from linkage_ros.study.tolerance import BATCH
    said = f'default 0: every core once a tolerance study has {POOL_FROM} batches of {BATCH} ' \
        'variants or more, a fit 2 starts or more; less work runs in this process'
    for command in ('tolerance', 'fit'):
        text = help_of(study_cli.main, [command, '--help'], capsys)
        assert said in ' '.join(text.split()), command
    doc = (ROOT / 'doc' / 'study.md').read_text()
    assert said in ' '.join(doc.split())
