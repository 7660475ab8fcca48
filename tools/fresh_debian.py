"""The Python side of tools/check-fresh-debian: what it reads and what it measures.

On the host: `mirror` prints the Debian mirror the machine's apt uses (from
/etc/apt/sources.list.d/*.sources and sources.list), and `sources` the
machine's Debian 12 sources (its updates and security too) as a sources.list,
so that the fresh root comes from the same registry and nothing else.
Inside the fresh root, after the README's main command has built the
workspace: `node-modules` lists every module of wall_follower.nodes (found by
walking the package, so that nodes moved into subpackages are found too);
`driven` waits until the robot has driven a distance on ground truth;
`move-arm` sends move_arm a goal to a named state.
Each check exits non-zero with a line saying what it saw.
"""
import argparse
import glob
import math
import os
import sys
import threading
import time

SUITE = 'bookworm'


def sources_entries(text, deb822):
    """(types, uris, suites, components) of each enabled entry of an apt sources file:
    deb822 stanzas (a .sources file) or one-line entries (`deb [options] URI SUITE
    COMPONENT...`)."""
    entries = []
    if deb822:
        for stanza in text.split('\n\n'):
            fields = {}
            for line in stanza.splitlines():
                if line.startswith('#') or ':' not in line or line[:1].isspace():
                    continue
                key, _, value = line.partition(':')
                fields[key.strip().lower()] = value.split()
            if fields.get('enabled', ['yes'])[0].lower() == 'no' or 'uris' not in fields:
                continue
            entries.append((fields.get('types', []), fields['uris'], fields.get('suites', []),
                            fields.get('components', [])))
        return entries
    for line in text.splitlines():
        words = line.split('#', 1)[0].split()
        if words and words[0] in ('deb', 'deb-src'):
            if len(words) > 1 and words[1].startswith('['):
                while words and not words[1].endswith(']'):
                    del words[1]
                del words[1]
            if len(words) >= 3:
                entries.append(([words[0]], [words[1]], [words[2]], words[3:]))
    return entries


def debian_sources(source_files, suite=SUITE):
    """(URI, suite, components) of each binary-package source of `suite` and its updates
    and security suites (`suite`-updates, ...) in the files given, in order; files that
    cannot be read are skipped."""
    found = []
    for path in source_files:
        try:
            with open(path) as stream:
                text = stream.read()
        except EnvironmentError:
            continue
        for types, uris, suites, components in sources_entries(text, path.endswith('.sources')):
            if 'deb' in types:
                found.extend((uri, name, components) for uri in uris for name in suites
                             if name == suite or name.startswith(suite + '-'))
    return found


def mirror(source_files, suite=SUITE):
    """The URI of the first binary-package source of `suite` itself; None if none names it."""
    return next((uri for uri, name, _ in debian_sources(source_files, suite) if name == suite),
                None)


def apt_source_files(etc='/etc/apt'):
    """The machine's apt source files, in apt's order."""
    return ([os.path.join(etc, 'sources.list')]
            + sorted(glob.glob(os.path.join(etc, 'sources.list.d', '*.list')))
            + sorted(glob.glob(os.path.join(etc, 'sources.list.d', '*.sources'))))


def node_modules(package_dir, package='wall_follower.nodes'):
    """Every module and subpackage below package_dir (the folder of `package`), dotted."""
    found = []
    for folder, dirs, files in os.walk(package_dir):
        dirs[:] = sorted(d for d in dirs if os.path.isfile(os.path.join(folder, d, '__init__.py')))
        relative = os.path.relpath(folder, package_dir)
        prefix = package if relative == '.' else package + '.' + relative.replace(os.sep, '.')
        if relative != '.':
            found.append(prefix)
        found.extend(prefix + '.' + name[:-3] for name in sorted(files)
                     if name.endswith('.py') and name != '__init__.py')
    return found


def driven(metres, limit):
    """Wait until ground truth shows `metres` of travel, at most `limit` wall seconds."""
    import rospy
    from nav_msgs.msg import Odometry

    lock = threading.Lock()
    state = {'last': None, 'total': 0.0}

    def on_truth(msg):
        p = msg.pose.pose.position
        with lock:
            if state['last'] is not None:
                state['total'] += math.hypot(p.x - state['last'][0], p.y - state['last'][1])
            state['last'] = (p.x, p.y)

    rospy.init_node('fresh_debian_driven', disable_signals=True)
    rospy.Subscriber('base_pose_ground_truth', Odometry, on_truth, queue_size=100)
    deadline = time.time() + limit
    while time.time() < deadline and not rospy.is_shutdown():
        with lock:
            total = state['total']
        if total >= metres:
            print('driven %.2f m (ground truth)' % total)
            return 0
        time.sleep(0.5)
    print('driven only %.2f m in %.0f s, not %.1f m (ground truth%s)' % (
        total, limit, metres, '' if state['last'] else ': none heard'))
    return 1


def move_arm(target, limit):
    """Send move_arm a goal to the SRDF state `target`; 0 once it succeeded."""
    import rospy
    from wall_follower.action_registration import action_server_registered
    from wall_follower.evaluation.goal_client import GoalClient
    from wall_follower.msg import MoveArmAction, MoveArmGoal

    rospy.init_node('fresh_debian_move_arm', disable_signals=True)
    # The client is made once the server is registered: made before, it can miss
    # the server's result topic for good (see action_registration.py).
    if not action_server_registered('move_arm', limit):
        print('no move_arm action server registered after %.0f s' % limit)
        return 1
    client = GoalClient('move_arm', MoveArmAction)
    if not client.wait_for_server(rospy.Duration(limit)):
        print('no move_arm action server after %.0f s' % limit)
        return 1
    client.send_goal(MoveArmGoal(named_target=target))
    if not client.wait_for_result(limit):
        print('move_arm did not finish the move to %r in %.0f s' % (target, limit))
        return 1
    result = client.get_result()
    print('move_arm to %r: %s (success %s, hand %.4f m from the goal)' % (
        target, result.message, result.success, result.position_error))
    return 0 if result.success else 1


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    commands = parser.add_subparsers(dest='command')
    commands.required = True
    commands.add_parser('mirror', help="the machine's Debian mirror")
    commands.add_parser('sources', help="the machine's Debian sources, as a sources.list")
    nodes = commands.add_parser('node-modules', help='the modules of wall_follower.nodes')
    nodes.add_argument('package_dir')
    drive = commands.add_parser('driven', help='wait for travel on ground truth')
    drive.add_argument('metres', type=float)
    drive.add_argument('--limit', type=float, default=120.0, help='wall seconds')
    arm = commands.add_parser('move-arm', help='move the arm to a named state')
    arm.add_argument('target')
    arm.add_argument('--limit', type=float, default=60.0, help='wall seconds')
    args = parser.parse_args(argv)
    if args.command == 'mirror':
        found = mirror(apt_source_files())
        if found is None:
            print('no apt source of %s found in %s' % (SUITE, ', '.join(apt_source_files())),
                  file=sys.stderr)
            return 1
        print(found)
        return 0
    if args.command == 'sources':
        for uri, suite, components in debian_sources(apt_source_files()):
            print('deb %s %s %s' % (uri, suite, ' '.join(components) or 'main'))
        return 0
    if args.command == 'node-modules':
        print('\n'.join(node_modules(args.package_dir)))
        return 0
    if args.command == 'driven':
        return driven(args.metres, args.limit)
    return move_arm(args.target, args.limit)


if __name__ == '__main__':
    sys.exit(main())
