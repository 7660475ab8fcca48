"""The student's own catkin workspace (`grade --workspace DIR`): the solution's environment.

A class names its package `wall_follower`, as the course does, so the
solution's package may share its name with grade's own: the two must
never meet in one environment. grade's own processes (the case runner,
the simulator, grade_case) run in grade's environment; the solution's
processes run in a clean one: a plain PATH, the system's ROS (its
/opt/ros/<distro>/setup.bash where there is one; Debian's ROS needs
none), then the workspace's devel/ (or install/) setup.bash, sourced in
the solution's sandbox (the setup is the student's code too) and read
back once. A workspace chained onto grade's own workspace is refused.

DIR may also be a package directory, or a workspace that was never built
(src/ only): its packages are copied into a private workspace in grade's
output directory (`--out`/workspace) and built there with catkin_make, in
a sandbox of its own without network, before any case runs.
"""
import os
import shutil
import subprocess

SETUPS = (('devel', 'setup.bash'), ('install', 'setup.bash'))
DEFAULT_PATH = '/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin'
# What a clean environment keeps of grade's: the locale and the terminal, nothing of ROS.
KEPT = ('LANG', 'LC_ALL', 'LANGUAGE', 'TERM', 'TZ')
# What the shell that sourced the setup leaves that is no one's environment.
SHELL_STATE = ('HOME', 'PWD', 'OLDPWD', 'SHLVL', '_')
# Wall seconds a private workspace may take to build, and its environment to be read.
BUILD_LIMIT = 900.0
SOURCE_LIMIT = 60.0
# The name of the private workspace in --out.
PRIVATE = 'workspace'
# A file every workspace holding grade's own package has: a workspace that holds it
# is grade's.
OWN_MARK = os.path.join('lib', 'wall_follower', 'grade')


def _sourcing(then):
    """A bash script that sources its arguments, in order, then runs then (a command line)."""
    return 'files=("$@"); set --; for f in "${files[@]}"; do . "$f"; done; exec ' + then


class WorkspaceError(Exception):
    """Why the workspace cannot give the solution an environment, in words."""


def setup_file(directory):
    """The workspace's devel/ (else install/) setup.bash; None if it has neither."""
    for parts in SETUPS:
        path = os.path.join(directory, *parts)
        if os.path.isfile(path):
            return path
    return None


def system_setup(environ=None):
    """The system's ROS setup.bash (/opt/ros/<distro>/), None where ROS needs none (Debian)."""
    distro = (os.environ if environ is None else environ).get('ROS_DISTRO', '')
    path = os.path.join('/opt/ros', distro, 'setup.bash')
    return path if distro and os.path.isfile(path) else None


def clean_environment(home):
    """A plain environment: PATH, the locale, HOME (and ROS_HOME) in home."""
    env = {key: os.environ[key] for key in KEPT if key in os.environ}
    env.update(PATH=DEFAULT_PATH, HOME=home, ROS_HOME=os.path.join(home, '.ros'))
    return env


def packages_to_build(directory):
    """The directories to copy into a private workspace's src/: [DIR] for a package,
    DIR/src's entries for a workspace never built; None when DIR is neither."""
    if os.path.isfile(os.path.join(directory, 'package.xml')):
        return [directory]
    source = os.path.join(directory, 'src')
    if os.path.isdir(source) and setup_file(directory) is None:
        entries = [os.path.join(source, name) for name in sorted(os.listdir(source))
                   if name != 'CMakeLists.txt']
        return [e for e in entries if os.path.isdir(e)] or None
    return None


def build(packages, workspace, wrap, log_path):
    """Copy packages into workspace/src (anew) and build it there with catkin_make.

    wrap(private, writable, network) wraps the build's command (its sandbox).
    Raises WorkspaceError, naming the log, when it does not build.
    """
    if os.path.exists(workspace):
        shutil.rmtree(workspace)
    source = os.path.join(workspace, 'src')
    os.makedirs(source)
    for package in packages:
        # Links stay links: followed here, they would copy what grade may read into it.
        shutil.copytree(package, os.path.join(source, os.path.basename(package.rstrip('/'))),
                        symlinks=True)
    home = os.path.join(workspace, 'home')
    os.makedirs(home)
    setups = [s for s in (system_setup(),) if s]
    command = ['bash', '-c', _sourcing('catkin_make -C %s' % _quoted(workspace)),
               'grade-build'] + setups
    command = wrap(home, writable=[workspace], network=False)(command)
    with open(log_path, 'w') as log:
        try:
            status = subprocess.call(command, env=clean_environment(home), stdout=log,
                                     stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                     timeout=BUILD_LIMIT)
        except subprocess.TimeoutExpired:
            raise WorkspaceError('the private workspace %s did not build within %.0f s (see %s)'
                                 % (workspace, BUILD_LIMIT, log_path))
    if status != 0 or setup_file(workspace) is None:
        with open(log_path) as log:
            last = [line.strip() for line in log.read().splitlines() if line.strip()][-2:]
        raise WorkspaceError('%s did not build (catkin_make exit %d; see %s): %s' % (
            ', '.join(packages), status, log_path, ' / '.join(last)))


def _quoted(path):
    return "'%s'" % path.replace("'", "'\\''")


def sourced_environment(setups, home, wrap):
    """The environment a clean shell has after sourcing setups, in order (run wrapped)."""
    command = wrap(home, network=False)(['bash', '-c', _sourcing('env -0'), 'grade-environment']
                                        + list(setups))
    try:
        result = subprocess.run(command, env=clean_environment(home), stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, stdin=subprocess.DEVNULL,
                                timeout=SOURCE_LIMIT)
    except subprocess.TimeoutExpired:
        raise WorkspaceError('sourcing %s did not end within %.0f s' % (
            ' then '.join(setups), SOURCE_LIMIT))
    if result.returncode != 0:
        raise WorkspaceError('sourcing %s failed: %s' % (
            ' then '.join(setups), result.stderr.decode(errors='replace').strip()[-300:]))
    env = {}
    for item in result.stdout.decode(errors='replace').split('\0'):
        if '=' in item:
            key, value = item.split('=', 1)
            env[key] = value
    for key in SHELL_STATE:
        env.pop(key, None)
    return env


def own_prefixes(environ=None):
    """The prefixes of grade's own workspace on CMAKE_PREFIX_PATH (realpaths)."""
    environ = os.environ if environ is None else environ
    return {os.path.realpath(p) for p in environ.get('CMAKE_PREFIX_PATH', '').split(os.pathsep)
            if p and os.path.exists(os.path.join(p, OWN_MARK))}


class StudentWorkspace(object):
    """--workspace DIR made ready: the workspace used (DIR, or the private one built from
    it), and the clean environment of the solution's processes."""

    def __init__(self, directory, out):
        self.given = os.path.abspath(directory)
        self.out = out
        self.directory = None
        self.environment = None

    def prepare(self, wrap, scratch):
        """Build (if DIR must be) and read the environment; raises WorkspaceError."""
        if not os.path.isdir(self.given):
            raise WorkspaceError('--workspace %s: no such directory' % self.given)
        packages = packages_to_build(self.given)
        if packages is not None:
            private = os.path.join(self.out, PRIVATE)
            build(packages, private, wrap, os.path.join(self.out, PRIVATE + '.log'))
            self.directory = private
        elif setup_file(self.given) is not None:
            self.directory = self.given
        else:
            raise WorkspaceError('--workspace %s is no catkin workspace (no devel/setup.bash '
                                 'or install/setup.bash) and no package (no package.xml)'
                                 % self.given)
        setups = [s for s in (system_setup(), setup_file(self.directory)) if s]
        home = os.path.join(scratch, 'workspace-home')
        os.makedirs(home, exist_ok=True)
        env = sourced_environment(setups, home, self.wrapper(wrap))
        shared = own_prefixes() & {os.path.realpath(p) for p in
                                   env.get('CMAKE_PREFIX_PATH', '').split(os.pathsep) if p}
        if shared:
            raise WorkspaceError(
                "--workspace %s was built on top of grade's own workspace (%s): build it in "
                "a shell that has not sourced grade's setup" % (
                    self.given, ', '.join(sorted(shared))))
        self.environment = env

    def wrapper(self, wrap):
        """wrap, with the workspace shown to the sandbox."""
        def wrapped(private, visible=(), writable=(), network=True):
            return wrap(private, visible=list(visible) + self.visible(), writable=writable,
                        network=network)
        return wrapped

    def visible(self):
        """What of the workspace a sandbox must show: it, and where the links in its src
        lead."""
        found = [self.directory]
        source = os.path.join(self.directory, 'src')
        if os.path.isdir(source):
            found += [os.path.realpath(os.path.join(source, n)) for n in os.listdir(source)
                      if os.path.islink(os.path.join(source, n))]
        return found
