"""What the package imports, it declares and installs (tools/dependencies.py's table).

Every import of the package's Python files, read with ast, is the standard library, this
package, a module beside the file, or in the dependency table with its rosdep key in
package.xml and its Debian package in the install list its kind needs; so are the ROS
packages the launch files start. A new `import foo` anywhere fails here, naming the file
and the import, until foo is declared. The checker itself is tested on small fake
checkouts.
"""
import importlib.util
import os
import sys

import pytest

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
SPEC = importlib.util.spec_from_file_location(
    'dependencies', os.path.join(REPO, 'tools', 'dependencies.py'))
dependencies = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(dependencies)

PACKAGE_XML = '''<?xml version="1.0"?>
<package format="3">
  <name>wall_follower</name>
  <buildtool_depend>catkin</buildtool_depend>
  %s
</package>
'''
WORKSPACE = 'REPO_DIR=x\nAPT_PACKAGES="catkin %s"\n'
RUN_TESTS = 'source workspace.sh\nAPT_PACKAGES="$APT_PACKAGES %s"\n'
TABLE = {
    'numpy': ('python3-numpy', 'python3-numpy', dependencies.RUN),
    'pytest': ('python3-pytest', 'python3-pytest', dependencies.TEST),
    'control_msgs': (None, None, dependencies.OPTIONAL),
}
OTHER = {'catkin': ('catkin', dependencies.BUILD)}


def checkout(root, files, depends='<exec_depend>python3-numpy</exec_depend>'
             '<test_depend>python3-pytest</test_depend>',
             main='python3-numpy', tests='python3-pytest'):
    """A fake checkout at root: package.xml, the two install lists, and files (path: text)."""
    os.makedirs(os.path.join(root, 'tools'))
    with open(os.path.join(root, 'package.xml'), 'w') as stream:
        stream.write(PACKAGE_XML % depends)
    with open(os.path.join(root, 'tools', 'workspace.sh'), 'w') as stream:
        stream.write(WORKSPACE % main)
    with open(os.path.join(root, 'tools', 'run-tests'), 'w') as stream:
        stream.write(RUN_TESTS % tests)
    for path, text in files.items():
        full = os.path.join(root, path)
        if not os.path.isdir(os.path.dirname(full)):
            os.makedirs(os.path.dirname(full))
        with open(full, 'w') as stream:
            stream.write(text)
    return dependencies.Checker(root, modules=TABLE, launched_packages={}, other=OTHER)


def test_every_import_and_launched_package_of_the_package_is_declared_and_installed():
    problems = dependencies.Checker(REPO).problems()
    assert not problems, 'undeclared dependencies:\n' + '\n'.join(problems)


def test_a_module_importing_an_undeclared_package_is_caught_by_file_and_line(tmp_path):
    checker = checkout(str(tmp_path), {
        'src/wall_follower/nodes/fake.py': '"""A node."""\nimport os\n\nimport foo.bar\n'})
    assert checker.problems() == [
        'src/wall_follower/nodes/fake.py:4: import foo is not in the dependency table '
        '(tools/dependencies.py): add its rosdep key, Debian package and kind']


def test_a_script_without_py_is_read_by_its_python_shebang(tmp_path):
    checker = checkout(str(tmp_path), {
        'scripts/fake_node': '#!/usr/bin/env python3\nfrom foo import bar\n',
        'scripts/notes.txt': 'import foo\n',
        'scripts/run.sh': '#!/bin/sh\nimport foo\n'})
    assert [line.split(': ')[0] for line in checker.problems()] == ['scripts/fake_node:2']


def test_a_key_missing_from_package_xml_is_named(tmp_path):
    checker = checkout(str(tmp_path), {'src/wall_follower/a.py': 'import numpy\n'},
                       depends='<test_depend>python3-pytest</test_depend>')
    assert checker.problems() == [
        'src/wall_follower/a.py:1: import numpy: package.xml does not declare python3-numpy '
        '(as exec_depend or depend)']


def test_a_run_time_key_declared_only_for_the_tests_is_the_wrong_kind(tmp_path):
    checker = checkout(str(tmp_path), {'src/wall_follower/a.py': 'import numpy\n'},
                       depends='<test_depend>python3-numpy</test_depend>'
                       '<test_depend>python3-pytest</test_depend>')
    assert 'package.xml does not declare python3-numpy' in ' '.join(checker.problems())


def test_a_debian_package_missing_from_its_install_list_is_named(tmp_path):
    checker = checkout(str(tmp_path), {'src/wall_follower/a.py': 'import numpy\n',
                                       'test/unit/test_a.py': 'import pytest\n'},
                       main='', tests='python3-numpy')
    assert checker.problems() == [
        "src/wall_follower/a.py:1: import numpy: its Debian package python3-numpy is not in "
        "the main command's (tools/workspace.sh) install list",
        "test/unit/test_a.py:1: import pytest: its Debian package python3-pytest is not in "
        "the test command's (tools/run-tests) install list"]


def test_a_test_only_module_imported_by_the_nodes_is_named(tmp_path):
    checker = checkout(str(tmp_path), {'src/wall_follower/a.py': 'import pytest\n'})
    assert checker.problems() == [
        'src/wall_follower/a.py:1: import pytest is test-only in the dependency table, but '
        'the nodes use it']


def test_an_optional_module_must_be_imported_under_an_import_error_guard(tmp_path):
    checker = checkout(str(tmp_path), {
        'src/wall_follower/guarded.py': 'try:\n    import control_msgs\n'
                                        'except ImportError:\n    control_msgs = None\n',
        'src/wall_follower/bare.py': 'import control_msgs.msg\n',
        'src/wall_follower/wrong_guard.py': 'try:\n    import control_msgs\n'
                                            'except ValueError:\n    pass\n'})
    assert [line.split(': ')[0] for line in checker.problems()] == [
        'src/wall_follower/bare.py:1', 'src/wall_follower/wrong_guard.py:2']


def test_standard_library_this_package_and_modules_beside_a_file_are_not_dependencies(
        tmp_path):
    checker = checkout(str(tmp_path), {
        'test/rostest/helper.py': 'import threading\n',
        'test/rostest/check_x.py': 'import collections.abc\nimport helper\n'
                                   'from wall_follower.nodes import common\nfrom . import y\n'})
    assert checker.problems() == []


def test_launched_packages_are_checked_and_a_solutions_own_folder_is_local(tmp_path):
    root = str(tmp_path)
    checkout(root, {
        'launch/a.launch': '<launch>\n  <node pkg="rviz" type="rviz" name="rviz"/>\n'
                           '  <include file="$(find wall_follower)/launch/b.launch"/>\n</launch>\n',
        'test/solutions/early/solution.launch': '<launch><node pkg="early" type="x"/></launch>\n'})
    checker = dependencies.Checker(root, modules=TABLE, other=OTHER, launched_packages={
        'rviz': ('rviz', 'rviz', dependencies.OPTIONAL)})
    assert checker.problems() == [
        'launch/a.launch:2: ROS package rviz: package.xml does not declare rviz (as exec_depend '
        'or depend)',
        "launch/a.launch:2: ROS package rviz: its Debian package rviz is not in the test "
        "command's (tools/run-tests) install list"]


def test_package_xml_keys_declared_twice_or_unexplained_are_named(tmp_path):
    checker = checkout(str(tmp_path), {}, depends='<exec_depend>python3-numpy</exec_depend>'
                       '<exec_depend>python3-numpy</exec_depend><exec_depend>foo</exec_depend>'
                       '<test_depend>python3-pytest</test_depend>')
    assert checker.problems() == [
        'package.xml: exec_depend python3-numpy is declared twice',
        'package.xml: exec_depend foo is not in the dependency table (tools/dependencies.py)']


def test_the_install_lists_are_read_from_the_scripts_without_running_them():
    main, tests = dependencies.install_lists(REPO)
    assert {'python3-opencv', 'python3-cv-bridge', 'catkin'} <= main
    assert 'python3-pytest' in tests - main
    assert not any(word.startswith('$') for word in tests)


@pytest.mark.skipif(not hasattr(sys, 'stdlib_module_names'), reason='Python 3.10+ only')
def test_the_standard_library_fallback_agrees_with_python_on_what_matters(monkeypatch):
    """The fallback (Python < 3.10) lists the folder's modules; where the interpreter has
    the real list, the two agree on the modules this package imports."""
    real = dependencies.stdlib_modules()
    monkeypatch.delattr(sys, 'stdlib_module_names')
    fallback = dependencies.stdlib_modules()
    used = set()
    for path, _ in dependencies.python_files(REPO):
        with open(path, encoding='utf-8') as stream:
            used.update(module for module, _, _ in dependencies.imports(stream.read()))
    assert used & real == used & fallback
    assert not fallback & set(dependencies.MODULES)
