"""The package's dependency table: where every module it imports and every ROS package it
uses comes from, and the check that code, package.xml and the install lists agree with it.

Each entry gives the rosdep key package.xml declares (so that `rosdep install
--from-paths src` on ROS Noetic installs it), the Debian 12 package that provides it
(installed by the README's commands), and its kind:

- RUN: the nodes need it. package.xml: exec_depend (or depend); Debian: the main
  command's install list (APT_PACKAGES of tools/workspace.sh).
- TEST: only the tests and tools/ import it. package.xml: test_depend (or exec_depend,
  depend); Debian: the test command's list (tools/run-tests adds to the main one).
- BUILD: the build needs it (setup.py, cfg/*.cfg, CMakeLists.txt). package.xml:
  build_depend, buildtool_depend or depend; Debian: the main command's list (it builds).
- OPTIONAL: used where installed, missing from Debian 12: imported only inside
  `try: ... except ImportError`, launched only when asked for. package.xml names its key
  only when given here (Noetic's rosdep then installs it); a Debian package given here
  is one the test command installs.

The check (test/unit/test_dependencies.py runs it; `python3 tools/dependencies.py`
prints the same) reads every Python file of src/, scripts/, cfg/, tools/, test/ and
setup.py (scripts without .py by their python shebang) with ast, and the launch and
rostest files, without running anything, and names each file and import that is
missing from the table or whose key or Debian package is not declared as its kind needs.
"""
import ast
import os
import re
import sys
import sysconfig
import xml.etree.ElementTree as ET

RUN, TEST, BUILD, OPTIONAL = 'run', 'test', 'build', 'optional'

# Top-level Python module -> (rosdep key, Debian package, kind).
MODULES = {
    'PIL': ('python3-pil', 'python3-pil', RUN),
    'actionlib': ('actionlib', 'python3-actionlib', RUN),
    'actionlib_msgs': ('actionlib_msgs', 'python3-actionlib-msgs', RUN),
    'catkin_pkg': ('python3-catkin-pkg', 'python3-catkin-pkg', BUILD),
    'control_msgs': (None, None, OPTIONAL),          # arm_controller's FollowJointTrajectory
    'cv2': ('python3-opencv', 'python3-opencv', RUN),
    'cv_bridge': ('cv_bridge', 'python3-cv-bridge', RUN),
    'dynamic_reconfigure': ('dynamic_reconfigure', 'python3-dynamic-reconfigure', RUN),
    'genpy': ('genpy', 'python3-genpy', RUN),
    'geometry_msgs': ('geometry_msgs', 'python3-geometry-msgs', RUN),
    'hypothesis': ('python3-hypothesis', 'python3-hypothesis', TEST),
    'matplotlib': ('python3-matplotlib', 'python3-matplotlib', RUN),
    'nav_msgs': ('nav_msgs', 'python3-nav-msgs', RUN),
    'numpy': ('python3-numpy', 'python3-numpy', RUN),
    'pytest': ('python3-pytest', 'python3-pytest', TEST),
    'rosdep2': ('python3-rosdep', 'python3-rosdep2', TEST),  # installed, never initialised
    'rosgraph': ('rosgraph', 'python3-rosgraph', RUN),
    'rosgraph_msgs': ('rosgraph_msgs', 'python3-rosgraph-msgs', RUN),
    'roslaunch': ('roslaunch', 'python3-roslaunch', RUN),
    'roslib': ('roslib', 'python3-roslib', RUN),
    'rosnode': ('rosnode', 'python3-rosnode', TEST),
    'rospkg': ('python3-rospkg', 'python3-rospkg', RUN),
    'rospy': ('rospy', 'python3-rospy', RUN),
    'rostest': ('rostest', 'python3-rostest', TEST),
    'scipy': ('python3-scipy', 'python3-scipy', RUN),
    'sensor_msgs': ('sensor_msgs', 'python3-sensor-msgs', RUN),
    'setuptools': ('python3-setuptools', 'python3-setuptools', BUILD),
    'std_msgs': ('std_msgs', 'python3-std-msgs', RUN),
    'std_srvs': ('std_srvs', 'python3-std-srvs', RUN),
    'tf2_msgs': ('tf2_msgs', 'python3-tf2-msgs', TEST),
    'tf2_ros': ('tf2_ros', 'python3-tf2-ros', RUN),
    'trajectory_msgs': ('trajectory_msgs', 'python3-trajectory-msgs', RUN),
    'visualization_msgs': ('visualization_msgs', 'python3-visualization-msgs', RUN),
    'yaml': ('python3-yaml', 'python3-yaml', RUN),
}

# ROS package whose node or file a launch or rostest file uses -> (key, Debian, kind).
LAUNCHED = {
    'controller_manager': (None, None, OPTIONAL),    # arm.launch controller:=gazebo
    'gazebo_ros': (None, None, OPTIONAL),            # arm.launch controller:=gazebo
    'gmapping': (None, None, OPTIONAL),              # slam.launch slam_methods:=gmapping
    'joint_state_publisher_gui': ('joint_state_publisher_gui', 'joint-state-publisher-gui',
                                  RUN),              # arm.launch gui:=true
    'robot_state_publisher': ('robot_state_publisher', 'ros-robot-state-publisher', RUN),
    'rviz': ('rviz', 'rviz', OPTIONAL),              # rviz:=true; rviz.test
}

# The rest of package.xml's keys -> (Debian package, kind): the build's, what a node
# finds at run time, and the programs the tests run.
OTHER = {
    'catkin': ('catkin', BUILD),
    'message_generation': ('ros-message-generation', BUILD),
    'message_runtime': ('ros-message-runtime', RUN),
    'bubblewrap': ('bubblewrap', RUN),               # grade's sandbox per case (bwrap)
    'stage_ros': (None, OPTIONAL),                   # stage_sim runs real stageros where found
    'chromium-browser': ('chromium', TEST),          # the grader's pages in a real browser
}

# package.xml's tags that satisfy each kind.
TAGS = {
    RUN: ('exec_depend', 'depend'),
    TEST: ('test_depend', 'exec_depend', 'depend'),
    BUILD: ('build_depend', 'buildtool_depend', 'depend'),
    OPTIONAL: ('exec_depend', 'depend'),
}
# What each kind of file may import or launch: the nodes only what they may install.
RUN_ROLE_KINDS = (RUN, OPTIONAL)
CODE_FOLDERS = {'src': RUN, 'scripts': RUN, 'cfg': BUILD, 'tools': TEST, 'test': TEST}
LAUNCH_FOLDERS = {'launch': RUN, 'test': TEST}
PACKAGE = 'wall_follower'
IMPORT_ERRORS = ('ImportError', 'ModuleNotFoundError')


def stdlib_modules():
    """Names of the standard library's top-level modules for this Python."""
    names = getattr(sys, 'stdlib_module_names', None)
    if names is not None:
        return frozenset(names)
    # Python < 3.10: the modules of the standard library's folder and its lib-dynload.
    found = set(sys.builtin_module_names)
    stdlib = sysconfig.get_paths()['stdlib']
    for folder in (stdlib, os.path.join(stdlib, 'lib-dynload')):
        for name in os.listdir(folder):
            if name.endswith(('.py', '.so', '.pyd')):
                found.add(name.split('.')[0])
            elif os.path.isfile(os.path.join(folder, name, '__init__.py')):
                found.add(name)
    return frozenset(found - {'site-packages', 'dist-packages'})


def is_python(path):
    """A .py file, or a file without an extension that starts with a python shebang."""
    if path.endswith('.py'):
        return True
    if os.path.splitext(path)[1]:
        return False
    try:
        with open(path, 'rb') as stream:
            first = stream.readline()
    except EnvironmentError:
        return False
    return first.startswith(b'#!') and b'python' in first


def python_files(repo):
    """(path, role) of every Python file of the package: role RUN, BUILD or TEST."""
    found = []
    setup = os.path.join(repo, 'setup.py')
    if os.path.isfile(setup):
        found.append((setup, BUILD))
    for folder, role in sorted(CODE_FOLDERS.items()):
        for top, dirs, files in os.walk(os.path.join(repo, folder)):
            dirs[:] = sorted(d for d in dirs if d != '__pycache__')
            found.extend((os.path.join(top, name), role) for name in sorted(files)
                         if is_python(os.path.join(top, name)))
    return found


def _catches_import_error(handler):
    names = handler.type.elts if isinstance(handler.type, ast.Tuple) else [handler.type]
    return any(isinstance(name, ast.Name) and name.id in IMPORT_ERRORS for name in names)


def imports(source, filename='<source>'):
    """(top-level module, line, guarded) of each absolute import in Python source;
    guarded: inside a try whose handlers catch ImportError."""
    found = []

    def visit(node, guarded):
        if isinstance(node, ast.Import):
            found.extend((alias.name.split('.')[0], node.lineno, guarded)
                         for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.append((node.module.split('.')[0], node.lineno, guarded))
        try_types = (ast.Try,) + ((ast.TryStar,) if hasattr(ast, 'TryStar') else ())
        if isinstance(node, try_types):
            body_guarded = guarded or any(_catches_import_error(h) for h in node.handlers
                                          if h.type is not None)
            for child in node.body:
                visit(child, body_guarded)
            for child in node.handlers + node.orelse + node.finalbody:
                visit(child, guarded)
            return
        for child in ast.iter_child_nodes(node):
            visit(child, guarded)

    visit(ast.parse(source, filename), False)
    return found


def is_local(module, path):
    """This package, or a module beside the file (a test's helper, a tool's library)."""
    folder = os.path.dirname(path)
    return (module == PACKAGE or os.path.isfile(os.path.join(folder, module + '.py'))
            or os.path.isfile(os.path.join(folder, module, '__init__.py')))


def declared(package_xml):
    """tag -> list of the keys package.xml declares with it (in order, repeats kept)."""
    keys = {}
    for element in ET.parse(package_xml).getroot():
        if isinstance(element.tag, str) and element.tag.endswith('depend'):
            keys.setdefault(element.tag, []).append((element.text or '').strip())
    return keys


APT_ASSIGNMENT = re.compile(r'^\s*APT_PACKAGES="([^"]*)"', re.M)


def apt_packages(script):
    """The Debian packages a script puts in APT_PACKAGES (its own words, not $APT_PACKAGES)."""
    with open(script) as stream:
        text = stream.read()
    return [word for value in APT_ASSIGNMENT.findall(text) for word in value.split()
            if not word.startswith('$')]


def install_lists(repo):
    """(main, test): what the README's main command installs (tools/workspace.sh), and what
    its test command installs (the same and tools/run-tests' own)."""
    main = set(apt_packages(os.path.join(repo, 'tools', 'workspace.sh')))
    return main, main | set(apt_packages(os.path.join(repo, 'tools', 'run-tests')))


LAUNCHED_PACKAGE = re.compile(r'''\bpkg="([\w-]+)"|\$\(find ([\w-]+)\)|find\('([\w-]+)'\)''')


def launched(repo):
    """(path, line, package, role) of each ROS package a launch or rostest file uses."""
    found = []
    for folder, role in sorted(LAUNCH_FOLDERS.items()):
        for top, dirs, files in os.walk(os.path.join(repo, folder)):
            dirs.sort()
            for name in sorted(files):
                if not name.endswith(('.launch', '.test')):
                    continue
                path = os.path.join(top, name)
                with open(path) as stream:
                    for number, line in enumerate(stream, 1):
                        for match in LAUNCHED_PACKAGE.finditer(line):
                            package = next(group for group in match.groups() if group)
                            found.append((path, number, package, role))
    return found


class Checker(object):
    """The problems of one checkout against the table (tables replaceable for tests)."""

    def __init__(self, repo, modules=None, launched_packages=None, other=None):
        self.repo = repo
        self.modules = MODULES if modules is None else modules
        self.launched = LAUNCHED if launched_packages is None else launched_packages
        self.other = OTHER if other is None else other
        self.keys = declared(os.path.join(repo, 'package.xml'))
        self.main, self.test = install_lists(repo)
        self.stdlib = stdlib_modules()

    def problems(self):
        """Lines 'FILE:LINE: what is wrong', relative to the repo; empty when all agree."""
        found = []
        for path, role in python_files(self.repo):
            with open(path, encoding='utf-8') as stream:
                source = stream.read()
            for module, line, guarded in imports(source, path):
                if module in self.stdlib or is_local(module, path):
                    continue
                for problem in self._entry_problems('import ' + module, self.modules.get(module),
                                                    role, guarded):
                    found.append('%s:%d: %s' % (os.path.relpath(path, self.repo), line, problem))
        for path, line, package, role in launched(self.repo):
            # A course solution's launch names its folder, made a package by `grade`.
            if package in (PACKAGE, os.path.basename(os.path.dirname(path))):
                continue
            for problem in self._entry_problems('ROS package ' + package,
                                                self.launched.get(package), role, True):
                found.append('%s:%d: %s' % (os.path.relpath(path, self.repo), line, problem))
        for key, (debian, kind) in sorted(self.other.items()):
            found.extend('package.xml: ' + problem for problem in self._entry_problems(
                'key ' + key, (key, debian, kind), kind, True))
        found.extend('package.xml: ' + problem for problem in self._package_xml_problems())
        return found

    def _entry_problems(self, what, entry, role, guarded):
        if entry is None:
            return ['%s is not in the dependency table (tools/dependencies.py): add its '
                    'rosdep key, Debian package and kind' % what]
        key, debian, kind = entry
        problems = []
        if kind == OPTIONAL and not guarded:
            problems.append('%s is optional (used where installed) but imported outside a '
                            '`try: ... except ImportError`' % what)
        if role == RUN and kind not in RUN_ROLE_KINDS:
            problems.append('%s is %s-only in the dependency table, but the nodes use it'
                            % (what, kind))
        if key is not None and not any(key in self.keys.get(tag, ()) for tag in TAGS[kind]):
            problems.append('%s: package.xml does not declare %s (as %s)'
                            % (what, key, ' or '.join(TAGS[kind])))
        if debian is not None:
            wanted, where = ((self.test, "the test command's (tools/run-tests)")
                             if kind in (TEST, OPTIONAL)
                             else (self.main, "the main command's (tools/workspace.sh)"))
            if debian not in wanted:
                problems.append('%s: its Debian package %s is not in %s install list'
                                % (what, debian, where))
        return problems

    def _package_xml_problems(self):
        """Keys declared twice, and keys the table does not explain."""
        known = set(entry[0] for table in (self.modules, self.launched)
                    for entry in table.values())
        known.update(self.other)
        problems = []
        seen = set()
        for tag, keys in sorted(self.keys.items()):
            for key in keys:
                if (tag, key) in seen:
                    problems.append('%s %s is declared twice' % (tag, key))
                seen.add((tag, key))
                if key not in known:
                    problems.append('%s %s is not in the dependency table (tools/dependencies.py)'
                                    % (tag, key))
        return problems


def main():
    repo = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
    problems = Checker(os.path.normpath(repo)).problems()
    for line in problems:
        print(line)
    print('%d dependency problem(s)' % len(problems) if problems else 'dependencies: all declared')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
