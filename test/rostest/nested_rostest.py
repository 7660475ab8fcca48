"""A rostest of the package run from inside another (on a master of its own), for the
checks that must write a world first, or need a package that may be missing."""
import subprocess
import tempfile

from wall_follower.evaluation.launching import LAUNCH_STOP_GRACE, ProcessGroup


def rostest_status(args, bound):
    """(exit status, output) of `rostest wall_follower ARGS...`, interrupted after bound
    wall seconds (as Ctrl-C; nothing it started outlives the call). Not --text: rostest
    then exits 0 whatever its tests say."""
    with tempfile.TemporaryFile('w+') as log:
        with ProcessGroup(grace=LAUNCH_STOP_GRACE) as group:
            process = group.start(['rostest', 'wall_follower'] + list(args), log=log)
            try:
                process.wait(timeout=bound)
            except subprocess.TimeoutExpired:
                group.end(process)
        log.seek(0)
        return process.returncode, log.read()
