"""Summarise catkin's JUnit results into one pass/fail line.

catkin_make run_tests exits 0 even when tests fail, so the suite's verdict
comes from the result files instead.
"""
import argparse
import glob
import os
import sys
import xml.etree.ElementTree as ET


def count_results(results_dir):
    """Return (passed, failed, failures) over every JUnit file below results_dir."""
    passed, failed, failures = 0, 0, []
    for path in sorted(glob.glob(os.path.join(results_dir, '**', '*.xml'), recursive=True)):
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as err:
            failed += 1
            failures.append('%s: unreadable result file (%s)' % (path, err))
            continue
        cases = root.iter('testcase')
        for case in cases:
            bad = case.find('failure')
            if bad is None:
                bad = case.find('error')
            if bad is not None:
                failed += 1
                failures.append('%s :: %s.%s: %s' % (
                    os.path.basename(path), case.get('classname'), case.get('name'),
                    (bad.get('message') or bad.text or '').strip()[:400]))
            elif case.find('skipped') is None:
                passed += 1
    return passed, failed, failures


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('results_dir')
    parser.add_argument('--compat-failed', type=int, default=0)
    parser.add_argument('--log', help='run_tests log to point at on failure')
    args = parser.parse_args()
    passed, failed, failures = count_results(args.results_dir)
    if args.compat_failed:
        failed += 1
        failures.append('vermin: code that Python 3.8 cannot run (see above)')
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
