"""grade's sandbox (evaluation/grading/sandbox.py), run for real: a command in a case's
namespaces and a solution's sandbox within them, started by root and by an ordinary user
(nobody, through setpriv), reaches nothing of the host: no port on its loopback, no file
outside its private directory, no process left once the case has ended, no hidden file."""
import os
import pwd
import shutil
import socket
import pathlib
import subprocess
import tempfile
import textwrap
import uuid

import pytest

from wall_follower.evaluation.grading import sandbox
from wall_follower.evaluation.launching import processes_with

NOBODY = pwd.getpwnam('nobody')
AS_NOBODY = ['setpriv', '--reuid=%d' % NOBODY.pw_uid, '--regid=%d' % NOBODY.pw_gid,
             '--clear-groups', '--']
# What the sandboxed command tries, each of it reported on a line of its output.
PROBE = textwrap.dedent('''
    import os, socket, subprocess, sys
    port, marker, private, secret, shown = sys.argv[1:6]
    print('uid', os.getuid())
    print('interfaces', ' '.join(n for _, n in socket.if_nameindex()))
    print('capabilities', [l.split()[1] for l in open('/proc/self/status')
                           if l.startswith('CapEff')][0])
    try:
        socket.create_connection(('127.0.0.1', int(port)), timeout=2).close()
        print('connected')
    except OSError:
        print('no connection')
    for path in ('/' + marker, '/tmp/' + marker, os.path.join(private, marker)):
        try:
            open(path, 'w').close()
            print('wrote', path)
        except OSError:
            print('could not write', path)
    for path in (secret, shown):
        try:
            print('read', open(path).read())
        except OSError:
            print('could not read', path)
    subprocess.Popen(['env', '-i', 'setsid', sys.executable, '-c',
                      'import time; time.sleep(120)', marker],
                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    print('started')
''')


def kernel_allows_user_namespaces():
    return subprocess.call(AS_NOBODY + ['unshare', '--user', '--map-root-user', 'true'],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL) == 0


@pytest.fixture
def base():
    """A directory an ordinary user can reach (pytest's own are root's alone)."""
    directory = tempfile.mkdtemp(prefix='grade-sandbox-test-')
    os.chmod(directory, 0o755)
    yield pathlib.Path(directory)
    shutil.rmtree(directory, ignore_errors=True)


@pytest.fixture
def listener():
    """A port on the host's loopback that records whoever connects."""
    server = socket.socket()
    server.bind(('127.0.0.1', 0))
    server.listen(5)
    server.settimeout(0.5)
    yield server
    server.close()


def accepted(server):
    try:
        server.accept()[0].close()
        return True
    except socket.timeout:
        return False


def run_probe(base, listener, privileged, prefix=()):
    """The probe run in a case's namespaces and a solution's sandbox; (its output, the
    marker of what it left, the private directory)."""
    marker = 'grade-sandbox-probe-%s' % uuid.uuid4().hex
    home = base / 'home'
    home.mkdir()
    (home / 'secret').write_text('the teacher\'s secret')
    (home / 'workspace').mkdir()
    (home / 'workspace' / 'shown').write_text('the student\'s workspace')
    private = base / 'private'
    private.mkdir()
    for directory in (home, home / 'workspace', private):
        os.chmod(str(directory), 0o755)
    os.chmod(str(home / 'workspace' / 'shown'), 0o644)
    if prefix:
        os.chown(str(private), NOBODY.pw_uid, NOBODY.pw_gid)
    confinement = sandbox.Confinement(str(private), hidden=[str(home)],
                                      visible=[str(home / 'workspace')],
                                      privileged=privileged)
    confinement.prepare()
    command = list(prefix) + sandbox.case_command(confinement.command(
        [sandbox.SOLUTION_PYTHON, '-c', PROBE, str(listener.getsockname()[1]), marker, str(private),
         str(home / 'secret'), str(home / 'workspace' / 'shown')]))
    output = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            universal_newlines=True, timeout=60).stdout
    return output, marker, private


def check_contained(output, marker, private, listener, uid):
    lines = output.splitlines()
    assert 'started' in lines, output
    assert 'uid %d' % uid in lines
    assert 'interfaces lo' in lines
    assert 'capabilities 0000000000000000' in lines
    assert 'no connection' in lines and not accepted(listener)
    assert 'could not write /%s' % marker in lines
    assert 'wrote /tmp/%s' % marker in lines and not os.path.exists('/tmp/' + marker)
    assert os.path.exists(os.path.join(str(private), marker))
    assert any(line.startswith('could not read') and line.endswith('secret') for line in lines)
    assert "read the student's workspace" in lines
    assert processes_with(marker) == []


@pytest.mark.skipif(os.geteuid() != 0, reason='grade is not run as root here')
def test_a_solution_started_by_root_runs_as_nobody_and_reaches_nothing(base, listener):
    output, marker, private = run_probe(base, listener, privileged=True)
    check_contained(output, marker, private, listener, NOBODY.pw_uid)


@pytest.mark.skipif(os.geteuid() != 0 or shutil.which('setpriv') is None,
                    reason='an ordinary user is made with setpriv, as root')
def test_the_sandbox_works_for_an_ordinary_user(base, listener):
    if not kernel_allows_user_namespaces():
        pytest.skip('this kernel allows no unprivileged user namespaces')
    output, marker, private = run_probe(base, listener, privileged=False,
                                        prefix=AS_NOBODY)
    check_contained(output, marker, private, listener, NOBODY.pw_uid)


def test_the_check_before_any_case_passes_here(tmp_path):
    assert sandbox.sandbox_problems(str(tmp_path)) == []


def test_without_bubblewrap_grade_says_so(tmp_path, monkeypatch):
    monkeypatch.setattr(sandbox, 'BWRAP', 'no-such-bwrap')
    (problem,) = sandbox.sandbox_problems(str(tmp_path))
    assert 'bubblewrap' in problem and '--no-sandbox' in problem


def test_what_lies_in_a_shown_directory_is_not_bound_again(tmp_path):
    inner = tmp_path / 'a' / 'b'
    inner.mkdir(parents=True)
    confinement = sandbox.Confinement(str(tmp_path), visible=[str(inner), str(tmp_path / 'a')])
    assert confinement.visible == [str(tmp_path / 'a')]
