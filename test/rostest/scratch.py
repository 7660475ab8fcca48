"""Scratch folders of the rostest checks, removed once their class is done.

A check that grades or maps writes megabytes of runs, plots and maps; left
in the temporary directory, every run of the suite would add to them.
"""
import shutil
import tempfile


class ScratchFolders(object):
    """A unittest.TestCase mixin: scratch(prefix) makes a folder that tearDownClass removes
    with everything written in it (by the check or by what it ran)."""

    @classmethod
    def scratch(cls, prefix):
        path = tempfile.mkdtemp(prefix=prefix)
        cls._scratch = cls.__dict__.get('_scratch', ()) + (path,)
        return path

    @classmethod
    def tearDownClass(cls):
        for path in cls.__dict__.get('_scratch', ()):
            shutil.rmtree(path, ignore_errors=True)
        super().tearDownClass()
