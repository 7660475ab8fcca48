"""setup.py installs every package of the library, so that an install space works as devel does.

In the devel space catkin points at src/ and any subpackage imports; an
install space (catkin_make install, a packaged release) holds only what
setup.py names. A list that forgot a folder passed every test here and
failed on the first import of an installed node.
"""
import os
import runpy

import setuptools

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def test_every_package_under_src_is_installed(monkeypatch):
    given = {}
    monkeypatch.setattr(setuptools, 'setup', lambda **kwargs: given.update(kwargs))
    monkeypatch.chdir(ROOT)
    runpy.run_path(os.path.join(ROOT, 'setup.py'))
    on_disk = set()
    src = os.path.join(ROOT, 'src')
    for folder, _dirs, files in os.walk(src):
        if '__init__.py' in files:
            on_disk.add(os.path.relpath(folder, src).replace(os.sep, '.'))
    assert on_disk - set(given['packages']) == set()
