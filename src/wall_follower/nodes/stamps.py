"""Message time stamps judged as plain seconds, so that no stamp can stop a node.

A header stamp is two uint32 fields: any time up to 2106, its nanoseconds
even beyond a second. The difference of two such times does not always fit
a Duration's 32-bit seconds: rospy raises, and tf2's C++ core aborts the
whole process ("Duration is out of dual 32-bit range", exit -6, no zero
Twist sent) when asked for a transform at a stamp some 68 years from the
data it holds. Stamps are compared here as float seconds, which hold any of
them, so that a stamp too far from now is refused before it reaches such
arithmetic.
"""


def stamp_problem(stamp, now, ahead, behind=None):
    """Why stamp (a rospy.Time, any value a message holds) is no use at ROS time now: more
    than ahead [s] after now, or more than behind [s] before it (None: any time before);
    None if it is within. The words name the bound, not the stamp, so that a warning of
    it repeats alike."""
    offset = stamp.to_sec() - now.to_sec()
    if offset > ahead:
        return 'stamped in the future (over %.3g s ahead of ROS time)' % ahead
    if behind is not None and -offset > behind:
        return 'stamped over %.3g s before ROS time' % behind
    return None
