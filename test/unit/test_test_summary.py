"""The suite's verdict: rostest wrappers must not hide a test node that ran nothing."""
import importlib.util
import os

HERE = os.path.dirname(__file__)
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
