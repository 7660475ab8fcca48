"""Waits that give up after wall seconds, also while simulated time stands still."""
import threading


def wait_in_wall_time(wait, timeout):
    """wait()'s answer if it comes within timeout wall seconds, else False.

    wait is a call that blocks until what it waits for is there, or until
    rospy shuts down (actionlib's wait_for_server() with no time-out, say).
    The time-outs of actionlib's waits are counted in ROS time, which
    stands still on simulated time while nobody publishes /clock: a wait
    meant to give up after some seconds would then wait for ever. This one
    counts wall seconds. A wait still blocked when they are up goes on in a
    daemon thread, which ends with rospy and never keeps the process alive.
    """
    answer = []
    thread = threading.Thread(target=lambda: answer.append(wait()))
    thread.daemon = True
    thread.start()
    thread.join(timeout)
    return bool(answer and answer[0])
