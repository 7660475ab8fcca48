"""SIGINT and SIGTERM for the package's nodes, answered from a node's first moment on.

A process started in the background by a shell (`rosrun ... &` in a
script) inherits SIGINT ignored, and Python keeps it ignored: a Ctrl-C that
lands while the node still imports rospy or registers with the master
(seconds on a loaded machine) would then be lost for good, and a node whose
handlers came only after rospy.init_node ran on. One started with SIGINT
at its default gets Python's own handler, which raises KeyboardInterrupt
wherever the main thread is; inside an import that can be swallowed (the
callback of importlib's module locks ignores what it raises, libraries
have bare `except:`), and the node goes on starting as if never
interrupted. So the first statement of every node's script puts SIGINT
back to the kernel's default action, through `_signal`, the C module that
`signal` wraps: the interpreter has loaded it already, so importing it
runs no Python code in which a KeyboardInterrupt could be raised. Then
importing wall_follower.nodes, which every such script does next, calls
catch(): from then on both signals are answered. (A signal that comes
before the script's first line, while the interpreter itself starts or a
shell still ignores it, is no node's to answer: rosrun's own look-ups,
seconds on a loaded machine, run with SIGINT as its shell leaves it.)

Until a node hands over its own answer (answer_with, which
nodes.shared.startup.init_node calls before rospy.init_node), a signal ends the
process at once: nothing has started that needs stopping. The kernel ends
it (the signals' default action), not Python: a Python handler runs only
between two bytecodes, so one that lands in a long import of a C library
(OpenCV's takes seconds on a loaded machine) would wait for it; and an
exception is no way either, as above. From then on the node's answer
is called in the main thread, wherever the signal caught it, so it must
only wake something up. A process that gives the signals to rospy
(rospy.init_node with its signal handlers) gets this handler called by
rospy's after its own; it then does nothing more.

The handlers are the process's, by nature global: this module holds the
one answer in force.
"""
import signal
import threading

SIGNALS = (signal.SIGINT, signal.SIGTERM)

_answers = []   # the node's answer, once it has handed one over


def catch():
    """Answer SIGINT and SIGTERM, ignored before or not: with the node's answer once it
    has handed one over, else by ending the process at once.

    Only the main thread may set handlers: from any other, nothing changes.
    """
    if threading.current_thread() is threading.main_thread():
        for number in SIGNALS:
            signal.signal(number, _on_signal if _answers else signal.SIG_DFL)


def answer_with(answer):
    """From now on answer a signal with answer(number), in the main thread."""
    _answers[:] = [answer]
    catch()


def _on_signal(number, _frame):
    if signal.getsignal(number) is not _on_signal:
        return     # called by rospy's handler, which has answered already
    _answers[0](number)
