"""nodes/shared/rosdep_lookup.py: rosdep put back as it was after dynamic_reconfigure's import."""
import sys

from wall_follower.nodes.shared import rosdep_lookup


def test_rosdep_is_put_back_as_it_was(monkeypatch):
    kept = object()
    monkeypatch.setitem(sys.modules, rosdep_lookup.ROSDEP_SORTING, kept)
    rosdep_lookup.import_dynamic_reconfigure()
    assert sys.modules[rosdep_lookup.ROSDEP_SORTING] is kept
    monkeypatch.delitem(sys.modules, rosdep_lookup.ROSDEP_SORTING)
    rosdep_lookup.import_dynamic_reconfigure()
    assert rosdep_lookup.ROSDEP_SORTING not in sys.modules
