"""The suite's verdict: rostest wrappers must not hide a test node that ran nothing, and a
unit-test module that fails to import fails its own tests, counted, and nothing else."""
import importlib.util
import os
import subprocess
import sys

HERE = os.path.dirname(__file__)
REPO = os.path.join(HERE, '..', '..')
SPEC = importlib.util.spec_from_file_location(
    'test_summary', os.path.join(HERE, '..', '..', 'tools', 'test_summary.py'))
summary = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(summary)

PASS = '<testcase classname="c" name="%s"/>'
FAIL = '<testcase classname="c" name="%s"><failure message="boom"/></testcase>'


def write(directory, name, cases):
    with open(os.path.join(str(directory), name), 'w') as stream:
        stream.write('<?xml version="1.0"?><testsuite>%s</testsuite>' % ''.join(cases))


def test_real_cases_are_counted_once(tmp_path):
    write(tmp_path, 'rostest-a.xml', [PASS % 'testa'])
    write(tmp_path, 'rosunit-a.xml', [PASS % 'x', PASS % 'y'])
    write(tmp_path, 'pytest-unit.xml', [PASS % 'z', FAIL % 'w'])
    passed, failed, failures = summary.count_results(str(tmp_path))
    assert (passed, failed) == (3, 1)
    assert 'boom' in failures[0]


def test_a_rostest_whose_node_ran_nothing_fails(tmp_path):
    write(tmp_path, 'rostest-a.xml', [PASS % 'testa'])
    write(tmp_path, 'rosunit-a.xml', [])
    passed, failed, _ = summary.count_results(str(tmp_path))
    assert (passed, failed) == (0, 1)


def test_a_missing_or_broken_node_result_fails(tmp_path):
    write(tmp_path, 'rostest-a.xml', [PASS % 'testa'])
    with open(os.path.join(str(tmp_path), 'rostest-b.xml'), 'w') as stream:
        stream.write('<?xml version="1.0"?>\n')
    passed, failed, _ = summary.count_results(str(tmp_path))
    assert (passed, failed) == (0, 2)


def test_a_failed_wrapper_counts(tmp_path):
    write(tmp_path, 'rostest-a.xml', [FAIL % 'testa'])
    write(tmp_path, 'rosunit-a.xml', [PASS % 'x'])
    passed, failed, _ = summary.count_results(str(tmp_path))
    assert (passed, failed) == (1, 1)


UNCOLLECTED = ('<testcase classname="" name="%s"><error message="collection failure">'
               'ImportError while importing test module\nE   ModuleNotFoundError: No module '
               'named &apos;foo&apos;</error></testcase>')
BROKEN_MODULE = """import foo


def test_one():
    pass


@pytest.mark.parametrize('x', [1, 2])
def test_two(x):
    pass


class TestThree(object):
    def test_three(self):
        pass

    def helper(self):
        pass
"""


def test_a_module_that_could_not_be_collected_fails_each_of_its_tests(tmp_path):
    os.makedirs(str(tmp_path / 'src' / 'test' / 'unit'))
    (tmp_path / 'src' / 'test' / 'unit' / 'test_broken.py').write_text(BROKEN_MODULE)
    write(tmp_path, 'pytest-unit.xml', [UNCOLLECTED % 'test.unit.test_broken', PASS % 'x'])
    passed, failed, failures = summary.count_results(str(tmp_path),
                                                     source=str(tmp_path / 'src'))
    assert (passed, failed) == (1, 3)
    assert failures == ["pytest-unit.xml :: test.unit.test_broken: could not be collected, so "
                        "its 3 test(s) did not run: ModuleNotFoundError: No module named 'foo'"]


def test_a_module_that_could_not_be_collected_nor_found_fails_once(tmp_path):
    write(tmp_path, 'pytest-unit.xml', [UNCOLLECTED % 'test.unit.gone'])
    passed, failed, _ = summary.count_results(str(tmp_path), source=str(tmp_path))
    assert (passed, failed) == (0, 1)


def test_pytest_as_the_runners_call_it_runs_the_other_modules_and_counts_the_broken_one(
        tmp_path):
    """With the flag both runners give (CMakeLists.txt's pytest target and
    tools/py38-unit-tests), a module that fails to import stops nothing else."""
    for runner in ('CMakeLists.txt', os.path.join('tools', 'py38-unit-tests')):
        with open(os.path.join(REPO, runner)) as stream:
            assert '--continue-on-collection-errors' in stream.read(), runner
    tests = tmp_path / 'tests'
    tests.mkdir()
    (tests / 'test_broken.py').write_text(BROKEN_MODULE)
    (tests / 'test_fine.py').write_text('def test_a():\n    pass\n\n\ndef test_b():\n'
                                        '    assert False\n')
    results = tmp_path / 'results'
    results.mkdir()
    subprocess.call([sys.executable, '-m', 'pytest', '-q', '-p', 'no:cacheprovider',
                     '--continue-on-collection-errors', str(tests),
                     '--junitxml=%s' % (results / 'pytest-unit.xml')],
                    stdout=subprocess.DEVNULL, cwd=str(tmp_path))
    passed, failed, _ = summary.count_results(str(results), source=str(tmp_path))
    assert (passed, failed) == (1, 1 + 3)
