"""Summarise catkin's JUnit results into one pass/fail line.

catkin_make run_tests exits 0 even when tests fail, so the suite's verdict
comes from the result files instead. A unit-test module that pytest could
not collect (it failed to import) ran none of its tests: each of them counts
as failed, so that the closing line counts every test that should have run.
"""
import argparse
import ast
import glob
import os
import sys
import xml.etree.ElementTree as ET

REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
# pytest's JUnit record of a module it could not collect: no class, this message.
COLLECTION_FAILURE = 'collection failure'


def _cases(path):
    """The testcase elements of a JUnit file; None if it is missing or unreadable."""
    try:
        return list(ET.parse(path).getroot().iter('testcase'))
    except (ET.ParseError, EnvironmentError):
        return None


def _problem(case):
    bad = case.find('failure')
    if bad is None:
        bad = case.find('error')
    if bad is None:
        return None
    return (bad.get('message') or bad.text or '').strip()[:400]


def module_tests(path):
    """How many tests a pytest module defines: its test_* functions and the test_* methods
    of its Test* classes (a parametrized one counts once); None if it cannot be read."""
    try:
        with open(path, encoding='utf-8') as stream:
            tree = ast.parse(stream.read(), path)
    except (EnvironmentError, SyntaxError, ValueError):
        return None
    functions = (ast.FunctionDef, ast.AsyncFunctionDef)
    count = 0
    for node in tree.body:
        if isinstance(node, functions) and node.name.startswith('test'):
            count += 1
        elif isinstance(node, ast.ClassDef) and node.name.startswith('Test'):
            count += sum(1 for item in node.body
                         if isinstance(item, functions) and item.name.startswith('test'))
    return count


def _uncollected(case, source):
    """(tests not run, failure line) for pytest's record of a module it could not collect,
    or None for any other case. source: the folder pytest's module names are relative to."""
    error = case.find('error')
    if case.get('classname') or error is None or error.get('message') != COLLECTION_FAILURE:
        return None
    module = case.get('name')
    tests = module_tests(os.path.join(source, *module.split('.')) + '.py')
    lines = [line[1:].strip() for line in (error.text or '').splitlines()
             if line.startswith('E ')]
    why = lines[-1] if lines else 'see the log'
    if tests is None:
        return 1, '%s: could not be collected, so none of its tests ran: %s' % (module, why)
    return max(tests, 1), '%s: could not be collected, so its %d test(s) did not run: %s' % (
        module, tests, why)


def count_results(results_dir, source=REPO):
    """Return (passed, failed, failures) over the JUnit files below results_dir.

    Each rostest writes a wrapper file (rostest-*.xml, one case per <test>)
    and the test node's own file (rosunit-<test-name>.xml). The real cases
    are counted from the latter; a wrapper counts only when it failed, or
    when its test node left no cases at all (rostest reports SUCCESS when a
    required node dies before the test runs). A unit-test module that could not be
    collected counts as failed once for each test it defines (source: the folder its
    dotted name is relative to, the repository).
    """
    passed, failed, failures = 0, 0, []
    files = sorted(glob.glob(os.path.join(results_dir, '**', '*.xml'), recursive=True))
    for path in files:
        name = os.path.basename(path)
        cases = _cases(path)
        if cases is None:
            failed += 1
            failures.append('%s: unreadable result file' % path)
            continue
        wrapper = name.startswith('rostest-')
        for case in cases:
            uncollected = _uncollected(case, source)
            if uncollected is not None:
                failed += uncollected[0]
                failures.append('%s :: %s' % (name, uncollected[1]))
                continue
            problem = _problem(case)
            if problem is not None:
                failed += 1
                failures.append('%s :: %s.%s: %s' % (name, case.get('classname'),
                                                     case.get('name'), problem))
                continue
            if not wrapper:
                if case.find('skipped') is None:
                    passed += 1
                continue
            test_name = case.get('name')[len('test'):]
            inner = _cases(os.path.join(os.path.dirname(path), 'rosunit-%s.xml' % test_name))
            if not inner:
                failed += 1
                failures.append('%s :: %s: the test node ran no test' % (name, test_name))
    return passed, failed, failures


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('results_dir')
    parser.add_argument('--failed-check', action='append', default=[], metavar='WHAT',
                        help='a check before the tests that failed, counted as one failure')
    parser.add_argument('--log', help='run_tests log to point at on failure')
    args = parser.parse_args()
    passed, failed, failures = count_results(args.results_dir)
    failed += len(args.failed_check)
    failures.extend(args.failed_check)
    if passed + failed == 0:
        failed = 1
        failures.append('no test results found in %s' % args.results_dir)
    for line in failures:
        print('FAILED ' + line)
    if failures and args.log:
        print('full test log: %s' % args.log)
    print('%d passed, %d failed' % (passed, failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main())
