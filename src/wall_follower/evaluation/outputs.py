"""Where the evaluation tools write their files (plots, figures), checked before a run.

A report written at the end of a lap, or of a set of trials, to a folder
that does not exist would lose the run to a traceback; each tool asks here
first and refuses to start instead.
"""
import os

__all__ = ['output_problem']


def output_problem(path):
    """Why no file can be written at path, in words; None when it may be."""
    directory = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(directory):
        return 'no directory %s for %s' % (directory, path)
    if os.path.isdir(path):
        return '%s is a directory' % path
    if not os.access(directory, os.W_OK):
        return 'cannot write in %s' % directory
    return None
