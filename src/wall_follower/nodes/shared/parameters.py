"""Every node's ~parameters, one way: checked at start, tunable live through dynamic_reconfigure.

A node names its table (wall_follower.params.<node>.TABLE) and, to be tuned
live, the config type generated from it (wall_follower.cfg.<Node>Config):

    params = NodeParameters(TABLE, WallFollowingConfig)
    ...
    update = params.take_update()     # in the node's loop, at each scan
    if update is not None:
        apply(update)

At start the node's private namespace is read once: a key the table does
not declare (a misspelling, say) is named in a warning, and a value of
the wrong type or out of range stops the node with an error naming it,
instead of a traceback or a default silently left in force. Then the
dynamic_reconfigure server starts (`rosrun dynamic_reconfigure dynparam
set /wall_following target_distance 0.22`, or rqt_reconfigure); it calls
back in its own thread, so a change is only stored here, under a lock, and
the node picks it up in its own thread at its next scan. A change that
cannot be used (not one of a parameter's choices, against a rule) fails
the set_parameters call, so that the client that asked is told too.
"""
import threading

import rospy
from dynamic_reconfigure.server import Server

from wall_follower.params import ParameterError, checked, names


class NodeParameters(object):
    """The current values of one node's parameters, and the changes made to them since."""

    def __init__(self, table, config_type=None, found=None, rules=(), read_at_start=()):
        """found: name -> a call that finds out the value of a parameter the node
        learns for itself (laser_x from tf, say), in force as if given on the
        parameter server; called only once the given values have passed their
        checks, so that a bad value stops the node at once, not after a wait.
        rules: what the values must satisfy together (see params.checked),
        at start and at each reconfiguration.
        read_at_start: names of parameters the node uses only at start (the
        size of a map being built, say): a live change to one is refused with
        a warning, and the value it started with stays in force."""
        self._table = table
        self._rules = rules
        self._read_at_start = tuple(read_at_start)
        self._lock = threading.Lock()
        self._values = _load(table, found or {}, rules, config_type is not None)
        self._version = 0
        self._taken = 0
        self.server = None
        if config_type is not None:
            self.server = Server(config_type, self._on_reconfigure)

    def snapshot(self):
        """name -> current value of every parameter (a copy, safe from any thread)."""
        with self._lock:
            return dict(self._values)

    def take_update(self):
        """Every current value if any changed since the last call, else None.

        For one consumer: the node's loop, which applies the values at its
        next scan.
        """
        with self._lock:
            if self._taken == self._version:
                return None
            self._taken = self._version
            return dict(self._values)

    def _on_reconfigure(self, config, _level):
        """dynamic_reconfigure's callback (its thread): keep the new values for the node.

        A change that cannot be used is refused as a failed service call:
        dynamic_reconfigure checks no enum value and no rule, and a config
        handed back with the old values would let `dynparam set` report
        success. The server then keeps and publishes nothing new.
        """
        try:
            given = dict((name, config[name]) for name in names(self._table))
            values = checked(self._table, given, self._rules)
        except ParameterError as error:
            rospy.logerr('%s: reconfiguration refused: %s', rospy.get_name(), error)
            raise rospy.ServiceException('reconfiguration refused: %s' % error)
        with self._lock:
            kept = [name for name in self._read_at_start if values[name] != self._values[name]]
            if kept:
                rospy.logwarn('%s: %s read at start only; kept as %s', rospy.get_name(),
                              ', '.join('~' + name for name in kept),
                              ', '.join(repr(self._values[name]) for name in kept))
                values.update((name, self._values[name]) for name in kept)
                config.update(values)
            changed = sorted(name for name in values if values[name] != self._values[name])
            if changed:
                rospy.loginfo('%s: %s (applied at the next scan)', rospy.get_name(), ', '.join(
                    '%s %r -> %r' % (name, self._values[name], values[name]) for name in changed))
                self._values = values
                self._version += 1
        return config


def _load(table, found, rules, tunable):
    """The node's ~parameters, and those found, checked against its table; exits with an
    error on bad values. rules: as NodeParameters'; tunable: the node will serve
    dynamic_reconfigure.

    Unknown keys only warn: the node may run on a parameter server that
    also holds settings for another version of it. The values read are
    written back converted (an int parameter given as 6.0 becomes 6), as
    dynamic_reconfigure's server reads them from the server again.
    """
    given = rospy.get_param('~', {})
    unknown = sorted(set(given) - set(names(table)))
    if unknown:
        if tunable:
            hint = '`rosrun dynamic_reconfigure dynparam get %s` lists' % rospy.get_name()
        else:
            hint = '%s are' % ', '.join('~' + name for name in names(table))
        rospy.logwarn('%s: ignoring unknown parameter(s) %s (misspelt? %s the known ones)',
                      rospy.get_name(), ', '.join('~' + name for name in unknown), hint)
    known = dict((name, value) for name, value in given.items() if name not in unknown)
    values = _checked_or_exit(table, known, rules)
    if found:
        known.update((name, find()) for name, find in found.items())
        values = _checked_or_exit(table, known, rules)
    for name in known:
        rospy.set_param('~' + name, values[name])
    return values


def _checked_or_exit(table, known, rules):
    """checked(table, known, rules), or the node's end with a line naming what is wrong."""
    try:
        return checked(table, known, rules)
    except ParameterError as error:
        rospy.logfatal('%s: cannot start: %s (check the launch file and config/*.yaml)',
                       rospy.get_name(), '; '.join('~' + problem for problem in error.problems))
        raise SystemExit(1)
