"""tools/fresh_debian.py: the mirror read from apt's sources, and the node modules found.

check-fresh-debian makes its root from the registry the machine's apt uses, in either
format apt reads, and imports every module of wall_follower.nodes, subpackages too.
"""
import importlib.util
import os

HERE = os.path.dirname(os.path.abspath(__file__))
SPEC = importlib.util.spec_from_file_location(
    'fresh_debian', os.path.join(HERE, '..', '..', 'tools', 'fresh_debian.py'))
fresh = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(fresh)

DEB822 = """Types: deb
# a comment
URIs: http://security.example/debian-security
Suites: bookworm-security
Components: main

Types: deb-src
URIs: http://src.example/debian
Suites: bookworm

Types: deb
URIs: http://off.example/debian
Suites: bookworm
Enabled: no

Types: deb
URIs: http://mirror.example/debian http://second.example/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
"""
ONE_LINE = """# deb http://commented.example/debian bookworm main
deb-src http://src.example/debian bookworm main
deb [arch=amd64 signed-by=/usr/share/keyrings/x.gpg] http://line.example/debian bookworm main
"""


def write(folder, name, text):
    path = os.path.join(str(folder), name)
    with open(path, 'w') as stream:
        stream.write(text)
    return path


def test_the_mirror_is_the_first_enabled_binary_source_of_bookworm(tmp_path):
    deb822 = write(tmp_path, 'debian.sources', DEB822)
    assert fresh.mirror([deb822]) == 'http://mirror.example/debian'
    assert fresh.mirror([write(tmp_path, 'sources.list', ONE_LINE)]) == 'http://line.example/debian'


def test_the_sources_are_bookworms_own_updates_and_security_only(tmp_path):
    files = [write(tmp_path, 'debian.sources', DEB822),
             write(tmp_path, 'other.list', 'deb http://vendor.example/apt stable main\n')]
    assert fresh.debian_sources(files) == [
        ('http://security.example/debian-security', 'bookworm-security', ['main']),
        ('http://mirror.example/debian', 'bookworm', ['main']),
        ('http://mirror.example/debian', 'bookworm-updates', ['main']),
        ('http://second.example/debian', 'bookworm', ['main']),
        ('http://second.example/debian', 'bookworm-updates', ['main'])]


def test_files_are_read_in_order_and_missing_ones_skipped(tmp_path):
    first = write(tmp_path, 'sources.list', '# nothing here\n')
    second = write(tmp_path, 'debian.sources', DEB822)
    assert fresh.mirror([os.path.join(str(tmp_path), 'gone.list'), first, second]) == \
        'http://mirror.example/debian'
    assert fresh.mirror([first]) is None


def test_the_source_files_are_apts(tmp_path):
    os.makedirs(str(tmp_path / 'sources.list.d'))
    for name in ('b.sources', 'a.list', 'c.disabled'):
        write(tmp_path / 'sources.list.d', name, '')
    assert [os.path.relpath(path, str(tmp_path)) for path in fresh.apt_source_files(
        str(tmp_path))] == ['sources.list', 'sources.list.d/a.list', 'sources.list.d/b.sources']


def test_node_modules_are_found_by_walking_the_package_subpackages_too(tmp_path):
    nodes = tmp_path / 'nodes'
    (nodes / 'arm').mkdir(parents=True)
    (nodes / 'data').mkdir()
    for path in ('__init__.py', 'b.py', 'a.py', 'notes.txt', 'arm/__init__.py', 'arm/move.py',
                 'data/not_a_package.py'):
        (nodes / path).write_text('')
    assert fresh.node_modules(str(nodes)) == [
        'wall_follower.nodes.a', 'wall_follower.nodes.b', 'wall_follower.nodes.arm',
        'wall_follower.nodes.arm.move']
