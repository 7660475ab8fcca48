"""How every node starts: rospy.init_node with SIGINT and SIGTERM answered from its first moment."""
import os
import threading

import rospy

from wall_follower.nodes.shared import signals


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

    threading.Thread(target=shut_down, name='shutdown', daemon=True).start()
    signals.answer_with(on_signal)
    try:
        rospy.init_node(name, disable_signals=True)
    except rospy.ROSInitException:
        if not caught:
            raise
    if caught:
        raise SystemExit(0)
