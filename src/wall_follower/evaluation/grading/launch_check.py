"""Whether roslaunch could load a solution's launch file: run by its path, in a child process.

Loading a launch file runs its substitutions ($(eval), a param's command),
so grade never loads one in its own process: options.solution_problems
runs this file by its path, in the environment (and, with grade's
sandbox, the sandbox) the cases give the solution. That environment may
hold the solution's own package named wall_follower, so this file
imports nothing of grade's package: only ROS's own roslaunch and rosgraph.

`python3 launch_check.py PACKAGE LAUNCH_FILE -- [ARG:=VALUE ...]` (or
`LAUNCH_PATH -- ...`) prints each problem on a line of its own, after
PROBLEM.
"""
import os
import sys

PROBLEM = 'grade-problem: '


def launch_path(launch):
    """(the launch file's path, []) for [PACKAGE, LAUNCH_FILE] or [PATH], as roslaunch
    finds it in this process's environment; (None, why not) when it would not."""
    if len(launch) != 2:
        return launch[0], []
    import rospkg
    import roslib.packages
    package, name = launch
    rospack = rospkg.RosPack()
    try:
        directory = rospack.get_path(package)
    except rospkg.ResourceNotFound:
        return None, ['no package %s on ROS_PACKAGE_PATH (%s)' % (
            package, os.environ.get('ROS_PACKAGE_PATH', ''))]
    found = roslib.packages.find_resource(package, name, rospack=rospack)
    if not found:
        return None, ['no launch file %s in package %s (%s)' % (name, package, directory)]
    if len(found) > 1:
        return None, ['%d launch files named %s in package %s (%s): give the path of one'
                      % (len(found), name, package, ', '.join(found))]
    return found[0], []


def problems(launch, args):
    """Why roslaunch could not start launch ([PACKAGE, LAUNCH_FILE] or [PATH]) with args."""
    path, found = launch_path(launch)
    return found if path is None else load_problems(path, args)


def load_problems(path, args):
    """Why roslaunch could not load path with args (ARG:=VALUE words); [] when it can."""
    import rosgraph.names
    import roslaunch.config
    import roslaunch.xmlloader
    given = rosgraph.names.load_mappings(args)
    unusable = [word for word in args if word.split(':=', 1)[0].strip() not in given]
    if unusable:
        return ['roslaunch takes no argument %s: ARG:=VALUE, ARG a name' % ', '.join(unusable)]
    loader = roslaunch.xmlloader.XmlLoader()
    try:
        loader.load(path, roslaunch.config.ROSLaunchConfig(), argv=['grade'] + list(args),
                    verbose=False)
    except Exception as err:  # whatever the file does wrong ($(eval) included) is reported
        return ['the launch file %s does not load: %s' % (
            path, ' '.join(str(err).split()) or type(err).__name__)]
    declared = loader.root_context.arg_names
    # __ns, __log and the like are roslaunch's own, not the file's.
    unknown = [name for name in given if not name.startswith('__') and name not in declared]
    if unknown:
        return ['the launch file %s declares no argument %s (it declares: %s)' % (
            path, ', '.join(unknown), ', '.join(declared) or 'none')]
    return []


if __name__ == '__main__':
    split = sys.argv.index('--')
    for problem in problems(sys.argv[1:split], sys.argv[split + 1:]):
        print(PROBLEM + problem)
