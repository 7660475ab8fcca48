"""tools/workspace.sh: one catkin workspace per clone, unless $WALL_FOLLOWER_WS names one.

A workspace shared by every clone links to whichever clone built it last, and rosrun fails
there once that clone is gone. The script is sourced from copies of it placed as two clones'
tools/ would be, with the cache in a temporary folder.
"""
import os
import shutil
import subprocess

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'tools',
                      'workspace.sh')


def workspace_of(clone, cache, override=None):
    """WS_DIR as the script sets it when sourced from clone/tools/."""
    tools = os.path.join(clone, 'tools')
    os.makedirs(tools)
    shutil.copy(SCRIPT, tools)
    env = dict(os.environ, XDG_CACHE_HOME=cache)
    env.pop('WALL_FOLLOWER_WS', None)
    if override is not None:
        env['WALL_FOLLOWER_WS'] = override
    done = subprocess.run(['bash', '-c', 'source "$1" && printf %s "$WS_DIR"', 'bash',
                           os.path.join(tools, 'workspace.sh')],
                          stdout=subprocess.PIPE, env=env, check=True,
                          universal_newlines=True)
    return done.stdout


def test_each_clone_has_a_workspace_of_its_own_named_after_it(tmp_path):
    cache = os.path.join(str(tmp_path), 'cache')
    first = workspace_of(os.path.join(str(tmp_path), 'one', 'wall_follower'), cache)
    second = workspace_of(os.path.join(str(tmp_path), 'two', 'wall_follower'), cache)
    assert first != second
    for workspace in (first, second):
        assert os.path.dirname(workspace) == os.path.join(cache, 'wall_follower_ws')
        assert os.path.basename(workspace).startswith('wall_follower-')


def test_the_same_clone_keeps_its_workspace(tmp_path):
    cache = os.path.join(str(tmp_path), 'cache')
    clone = os.path.join(str(tmp_path), 'clone')
    first = workspace_of(clone, cache)
    shutil.rmtree(clone)
    assert workspace_of(clone, cache) == first


def test_wall_follower_ws_names_the_workspace_as_before(tmp_path):
    chosen = os.path.join(str(tmp_path), 'my_ws')
    assert workspace_of(os.path.join(str(tmp_path), 'clone'), os.path.join(str(tmp_path), 'c'),
                        override=chosen) == chosen
