"""tools/make_world_bitmaps.py loaded as a module, for the tests that hold worlds/ to it.

Shared by the unit tests (not itself a test module): tools/ is no package.
"""
import importlib.util
import os

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)


def generator():
    spec = importlib.util.spec_from_file_location(
        'make_world_bitmaps', os.path.join(REPO, 'tools', 'make_world_bitmaps.py'))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module
