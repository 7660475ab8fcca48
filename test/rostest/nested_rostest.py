"""A rostest of the package run from inside another (on a master of its own), for the
checks that must write a world first, or need a package that may be missing."""
import os
import signal
import subprocess
import tempfile


def rostest_status(args, bound):
    """(exit status, output) of `rostest wall_follower ARGS...`, interrupted after bound
    wall seconds. Not --text: rostest then exits 0 whatever its tests say."""
    with tempfile.TemporaryFile('w+') as log:
        process = subprocess.Popen(['rostest', 'wall_follower'] + list(args), stdout=log,
                                   stderr=subprocess.STDOUT, start_new_session=True)
        try:
            status = process.wait(timeout=bound)
        except subprocess.TimeoutExpired:
            # Ctrl-C to its whole group, so that rostest takes its nodes down too.
            os.killpg(process.pid, signal.SIGINT)
            status = process.wait()
        log.seek(0)
        return status, log.read()
