"""Whether roslaunch could load a solution's launch file: run by its path, in a child process.

Loading a launch file runs its substitutions ($(eval), a param's command),
so grade never loads one in its own process: options.solution_problems
runs this file by its path, in the environment (and, with grade's
sandbox, the sandbox) the cases give the solution. That environment may
hold the solution's own package named wall_follower, so this file
imports nothing of grade's package: only ROS's own roslaunch and rosgraph.

`python3 launch_check.py LAUNCH_FILE [ARG:=VALUE ...]` prints each problem
on a line of its own, after PROBLEM.
"""
import sys

PROBLEM = 'grade-problem: '


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
    for problem in load_problems(sys.argv[1], sys.argv[2:]):
        print(PROBLEM + problem)
