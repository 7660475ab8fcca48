"""A sandbox per case, and one for everything of a solution grade runs outside a case.

A case runs in namespaces of its own (bubblewrap, `bwrap`): its own PID
namespace, so that every process of the case ends with it whatever it did
to its session or environment (when the case's first process ends, the
kernel kills every other); its own network namespace, with only a
loopback interface, so that nothing in it reaches the host's ports,
another case's master or the outside; its own IPC namespace. grade's own
processes of the case (the master, the simulator, the grade_case node)
run there with the normal filesystem, so that they write the case's
record; the solution runs in a second sandbox nested in it (Confinement):
its own PID namespace again, the whole filesystem read-only, the home
directories and grade's output directory hidden, a private writable
directory (its HOME and ROS_HOME), a private /tmp (also /var/tmp and
/dev/shm) and an empty /run, no capabilities, and, when grade runs as
root, the uid of `nobody`. So the solution cannot touch the case's
record, see or signal grade's processes, or read root's files.

What it does not do: the ROS graph of the case is shared (it must be, to
grade), so a solution can still talk to the case's master, simulator and
grade_case node over ROS; files that every user may read stay readable;
CPU and memory are not limited beyond --timeout.

As root, bwrap needs no user namespace; as an ordinary user it needs
unprivileged user namespaces (Debian 12 allows them). sandbox_problems()
tries a whole sandboxed command before any case runs.

`python3 -m wall_follower.evaluation.grading.sandbox hold SPEC` is what runs
first inside a case's namespaces (hold()): it starts grade's own processes
and then the solution, waits for the case to end, and writes how it ended.
"""
import json
import os
import pwd
import shutil
import subprocess
import sys

from wall_follower.evaluation.launching import ProcessGroup, wait_for_port

BWRAP = 'bwrap'
# The unprivileged user a solution runs as when grade runs as root.
UNPRIVILEGED = 'nobody'
# The interpreter a solution's Python nodes run with (the shebang of ROS 1's own scripts,
# Debian's and Noetic's alike). The check tries it, not grade's own interpreter, which
# may be one that the unprivileged user cannot reach (a virtual environment in a home).
SOLUTION_PYTHON = '/usr/bin/python3'
# Wall seconds the check before any case may take.
CHECK_LIMIT = 60.0
# Wall seconds for a case's master to come up.
MASTER_LIMIT = 30.0
# Where a solution may write beside its private directory: each is the private
# directory's TEMPORARY, empty at the start of each case.
TEMPORARY_DIRECTORIES = ('/tmp', '/var/tmp', '/dev/shm')
TEMPORARY = '.tmp'
# Directories of system state a solution has no business with: an empty one each.
EMPTIED_DIRECTORIES = ('/run',)
PRIVATE_SYSTEM_DIRECTORIES = TEMPORARY_DIRECTORIES + EMPTIED_DIRECTORIES
# What a case's processes and a solution in its sandbox use for ROS: the namespace has
# only loopback, on which the host's name need not resolve.
LOOPBACK_ENVIRONMENT = {'ROS_IP': '127.0.0.1', 'ROS_HOSTNAME': 'localhost'}
# The search paths of an environment, whose directories a solution must see.
PATH_VARIABLES = ('PATH', 'PYTHONPATH', 'ROS_PACKAGE_PATH', 'CMAKE_PREFIX_PATH',
                  'LD_LIBRARY_PATH', 'PKG_CONFIG_PATH')


def running_as_root():
    return os.geteuid() == 0


def unprivileged_ids():
    """(uid, gid) of UNPRIVILEGED."""
    entry = pwd.getpwnam(UNPRIVILEGED)
    return entry.pw_uid, entry.pw_gid


def case_command(command):
    """command run as a case's first process: PID, network and IPC namespaces of its own,
    the normal filesystem (grade's own processes write the case's record there)."""
    return [BWRAP, '--dev-bind', '/', '/', '--proc', '/proc', '--unshare-pid', '--unshare-net',
            '--unshare-ipc', '--die-with-parent', '--'] + list(command)


def hidden_directories(out):
    """What no solution sees: the home directories (root's, every user's, the grading
    user's) and grade's output directory (every case's record, other students' grades)."""
    return [d for d in ('/root', '/home', os.path.expanduser('~'), os.path.abspath(out))
            if os.path.isdir(d)]


def needed_paths(environment, keys=PATH_VARIABLES):
    """The directories an environment's search paths name (and where their links lead, one
    level into each ROS_PACKAGE_PATH directory): what a solution must see of them."""
    found = set()
    for key in keys:
        for entry in environment.get(key, '').split(os.pathsep):
            if os.path.isabs(entry) and os.path.exists(entry):
                found.update((entry, os.path.realpath(entry)))
                if key == 'ROS_PACKAGE_PATH' and os.path.isdir(entry):
                    for name in os.listdir(entry):
                        link = os.path.join(entry, name)
                        if os.path.islink(link):
                            found.add(os.path.realpath(link))
    return sorted(found)


class Containment(object):
    """The sandboxes of one grading (enabled), or none: wrap() gives the wrapper of a
    solution's command, hiding hidden_directories(out)."""

    def __init__(self, enabled, out):
        self.enabled = enabled
        self.hidden = hidden_directories(out)

    def wrap(self, private, visible=(), writable=(), network=True):
        """A function command -> the command run in a Confinement (itself without one)."""
        if not self.enabled:
            return list
        confinement = Confinement(private, self.hidden, visible, writable, network)
        confinement.prepare()
        return confinement.command


def _ancestors_below(path, top):
    """The directories strictly between top and path, outermost first."""
    found = []
    parent = os.path.dirname(path)
    while parent != top and parent.startswith(top + os.sep):
        found.append(parent)
        parent = os.path.dirname(parent)
    return found[::-1]


def _under(path, directory):
    return path == directory or path.startswith(directory.rstrip(os.sep) + os.sep)


class Confinement(object):
    """How a solution's command runs: read-only, hidden from grade's files, unprivileged.

    private: its one writable directory (it exists); hidden: directories
    it must not see (the home directories, grade's output), each made an
    empty one; visible: directories under those that it needs (its
    workspace, its launch file's directory), read-only; writable: more
    directories it may write (a workspace it builds); network: False
    for a network namespace of its own (commands run outside a case: a
    build, a check), True to share the case's; privileged: whether the
    command is started by root (by default: whether grade runs as root),
    which then makes it nobody.
    """

    def __init__(self, private, hidden=(), visible=(), writable=(), network=True,
                 privileged=None):
        self.privileged = running_as_root() if privileged is None else privileged
        self.private = os.path.abspath(private)
        self.hidden = sorted({os.path.abspath(p) for p in hidden if os.path.isdir(p)})
        shown = sorted({os.path.abspath(p) for p in visible if os.path.exists(p)})
        # What lies in a directory shown is shown with it.
        self.visible = [p for p in shown if not any(_under(p, q) and p != q for q in shown)]
        self.writable = sorted({os.path.abspath(p) for p in writable if os.path.isdir(p)})
        self.network = network

    @property
    def temporary(self):
        return os.path.join(self.private, TEMPORARY)

    def prepare(self):
        """Make its temporary directory, and give the private and writable directories to
        the user the solution runs as."""
        os.makedirs(self.temporary, exist_ok=True)
        os.chmod(self.temporary, 0o1777)
        if self.privileged:
            uid, gid = unprivileged_ids()
            for top in [self.private] + self.writable:
                for root, directories, files in os.walk(top):
                    for name in [root] + [os.path.join(root, n) for n in directories + files]:
                        os.lchown(name, uid, gid)

    def command(self, command):
        """command, run so. (Options of bubblewrap 0.4, Ubuntu 20.04's, and later; a
        directory it makes is 0755, which the solution's user can go through.)"""
        args = [BWRAP, '--ro-bind', '/', '/', '--dev', '/dev', '--proc', '/proc']
        for directory in EMPTIED_DIRECTORIES:
            args += ['--tmpfs', directory]
        for directory in TEMPORARY_DIRECTORIES:
            args += ['--bind', self.temporary, directory]
        hidden = [h for h in self.hidden if h not in PRIVATE_SYSTEM_DIRECTORIES]
        for directory in hidden:
            args += ['--tmpfs', directory]
        made = set()
        for path in self.visible + self.writable + [self.private]:
            covers = [h for h in hidden + list(PRIVATE_SYSTEM_DIRECTORIES) if _under(path, h)]
            for top in covers:
                for parent in _ancestors_below(path, top):
                    if parent not in made:
                        made.add(parent)
                        args += ['--dir', parent]
            if path in self.visible and covers:
                args += ['--ro-bind', path, path]
        # What is hidden stays so inside what is shown again (grade's output in a workspace).
        for directory in hidden:
            if any(_under(directory, v) and directory != v for v in self.visible):
                args += ['--tmpfs', directory]
        for path in self.writable + [self.private]:
            args += ['--bind', path, path]
        args += ['--unshare-pid', '--unshare-ipc', '--unshare-uts', '--new-session',
                 '--die-with-parent', '--chdir', self.private]
        if not self.network:
            args.append('--unshare-net')
        if self.privileged:
            # Only what setpriv needs to become nobody; it drops those too.
            args += ['--cap-drop', 'ALL', '--cap-add', 'CAP_SETUID', '--cap-add', 'CAP_SETGID',
                     '--cap-add', 'CAP_SETPCAP', '--']
            uid, gid = unprivileged_ids()
            args += ['setpriv', '--reuid=%d' % uid, '--regid=%d' % gid, '--clear-groups',
                     '--inh-caps=-all', '--bounding-set=-all', '--no-new-privs']
        return args + ['--'] + list(command)


def sandbox_problems(scratch):
    """[] when a solution's command runs sandboxed in a case here; else why not, in words.

    Tried, not guessed: a command in a case's namespaces, and in a
    solution's sandbox within them, that must see only loopback and a
    read-only filesystem.
    """
    if shutil.which(BWRAP) is None:
        return ['no sandbox: bubblewrap (%s) is not installed (Debian: apt-get install '
                'bubblewrap); --no-sandbox grades without one' % BWRAP]
    if running_as_root() and shutil.which('setpriv') is None:
        return ['no sandbox: setpriv (util-linux) is missing; --no-sandbox grades without one']
    private = os.path.join(scratch, 'sandbox-check')
    os.makedirs(private, exist_ok=True)
    confinement = Confinement(private)
    confinement.prepare()
    probe = ('import os, socket; assert [n for _, n in socket.if_nameindex()] == ["lo"]; '
             'assert not os.access("/", os.W_OK); '
             'open(os.path.join(%r, "ok"), "w").close()' % private)
    command = case_command(confinement.command([SOLUTION_PYTHON, '-c', probe]))
    try:
        result = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                stdin=subprocess.DEVNULL, universal_newlines=True,
                                timeout=CHECK_LIMIT)
    except subprocess.TimeoutExpired:
        return ['no sandbox: a sandboxed command did not end within %.0f s; --no-sandbox '
                'grades without one' % CHECK_LIMIT]
    if result.returncode != 0 or not os.path.exists(os.path.join(private, 'ok')):
        said = ' / '.join(result.stdout.strip().splitlines()[-3:]) or 'exit %d' % (
            result.returncode)
        return ['no sandbox: bubblewrap cannot make one here (%s)%s; --no-sandbox grades '
                'without one' % (said, '' if running_as_root() else
                                 ': as an ordinary user it needs unprivileged user namespaces')]
    return []


def hold(spec, group):
    """Run a case's processes in group (a ProcessGroup) and say how the case ended.

    spec (grader.CaseRunner's): the harness's command and environment,
    the master's port, the solution's (wrapped) command and environment,
    the wall seconds the case may take, the two logs, the group's token.
    Returns (how it ended in words, whether grade's own harness ended it):
    grade_case.launch ends by itself only once grade_case has ended, which
    writes the record first unless the harness failed. The processes are
    the caller's to end.
    """
    with open(spec['log'], 'a') as log, open(spec['solution_log'], 'a') as solution_log:
        watcher = group.start(spec['harness'], spec['harness_env'], log)
        if not wait_for_port(spec['port'], MASTER_LIMIT, watcher):
            return 'its master did not start', True
        group.start(spec['solution'], spec['solution_env'], solution_log)
        try:
            watcher.wait(timeout=spec['timeout'])
        except subprocess.TimeoutExpired:
            return 'it ran out of its %.0f wall seconds' % spec['timeout'], False
    return "grade's simulator or grade_case node ended", True


def main(argv):
    """hold SPEC OUTCOME: the case of SPEC (JSON), how it ended into OUTCOME (JSON)."""
    if len(argv) != 3 or argv[0] != 'hold':
        sys.stderr.write('usage: python3 -m %s hold SPEC OUTCOME\n' % __name__)
        return 2
    with open(argv[1]) as stream:
        spec = json.load(stream)
    # Nothing to stop: when this process ends, the case's namespace ends, and with it every
    # process still in it.
    ended, harness_failed = hold(spec, ProcessGroup(spec['token']))
    with open(argv[2], 'w') as stream:
        json.dump({'ended': ended, 'harness_failed': harness_failed}, stream)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
