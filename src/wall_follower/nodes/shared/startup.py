"""How every node starts: rospy.init_node with SIGINT and SIGTERM answered from its first moment."""
import os
import sys
import threading

import rosgraph
import rospy

from wall_follower.nodes.shared import signals
from wall_follower.nodes.shared.shutdown import poll_until

# Wall seconds between two tries to reach a master that does not answer.
MASTER_RETRY = 1.0
# Wall seconds between two looks, meanwhile, for a signal.
SIGNAL_POLL = 0.05


def master_answers():
    """True when the ROS master answers at all (getPid), False while nothing listens there."""
    try:
        rosgraph.Master(rospy.get_name()).getPid()
    except OSError:
        return False
    return True


def _wait_for_master(name, caught):
    """Until the master answers; False if a signal (in caught) came first.

    Said once on stderr, as rospy's logging is not set up yet: a node
    started before roscore otherwise waits without a word.
    """
    said = False
    while not caught:
        if master_answers():
            return True
        if not said:
            sys.stderr.write('%s: waiting for the ROS master at %s\n'
                             % (name, rosgraph.get_master_uri()))
            said = True
        poll_until(lambda: caught, MASTER_RETRY, SIGNAL_POLL)
    return False


def init_node(name):
    """rospy.init_node, with SIGINT and SIGTERM answered from a thread of the node's own.

    rospy runs its shutdown hooks inside its signal handler, that is in the
    main thread wherever the signal caught it. A hook that publishes (every
    driving node's last stop) then deadlocks on a publisher lock whenever
    the signal lands while the main thread is publishing, and the node
    never exits. Here the handler only wakes a thread that shuts rospy down,
    by a byte written to a pipe: it takes no lock, so a second signal that
    lands while the first is being answered cannot block on one.

    The handler is in force before rospy.init_node starts, which can take
    seconds (registering with the master, reading /use_sim_time): a signal
    then ends the start-up, and the node exits quietly, having driven
    nothing. (Before this call, nodes.signals answers.)

    rospy.init_node is called only once the master answers. Without one,
    rospy retries the registration of its /rosout publisher for ever while
    it holds the topic manager's lock, and rospy.signal_shutdown waits for
    that lock before it marks rospy shut down: a node started before
    roscore would never end on a signal. Waiting here, a signal ends it
    at once.
    """
    caught = []
    wake_read, wake_write = os.pipe()
    os.set_blocking(wake_write, False)   # a pipe full of signals already holds a wake-up

    def shut_down():
        number = os.read(wake_read, 1)[0]
        rospy.signal_shutdown('signal %d' % number)

    def on_signal(number):
        caught.append(number)
        try:
            os.write(wake_write, bytes([number]))
        except BlockingIOError:
            pass

    signals.answer_with(on_signal)
    if not _wait_for_master(name, caught):
        raise SystemExit(0)
    # Only now: a signal while no rospy runs has nothing of it to shut down.
    threading.Thread(target=shut_down, name='shutdown', daemon=True).start()
    try:
        rospy.init_node(name, disable_signals=True)
    except rospy.ROSInitException:
        if not caught:
            raise
    if caught:
        raise SystemExit(0)
