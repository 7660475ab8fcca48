"""The arm's description from the parameter server, as MoveIt keeps it: the URDF in
robot_description, the SRDF in robot_description_semantic, joint_limits.yaml under
robot_description_planning. A missing or unusable one stops the node with one line
saying which (arm.launch loads them all); arm_controller alone can do without the last.
"""
import numpy as np
import rospy

from wall_follower.arm.model import (ModelError, read_acceleration_limits, read_srdf, read_urdf,
                                     read_velocity_limits)

DESCRIPTION = 'robot_description'
SEMANTIC = DESCRIPTION + '_semantic'
PLANNING = DESCRIPTION + '_planning'


def _param(name):
    if not rospy.has_param(name):
        _fail('no parameter %s (start the arm with `roslaunch wall_follower arm.launch`)'
              % rospy.resolve_name(name))
    return rospy.get_param(name)


def _fail(problem):
    rospy.logfatal('%s: cannot start: %s', rospy.get_name(), problem)
    raise SystemExit(1)


def arm_model():
    """The ArmModel of robot_description."""
    try:
        return read_urdf(str(_param(DESCRIPTION)))
    except ModelError as error:
        _fail('%s: %s' % (rospy.resolve_name(DESCRIPTION), error))


def arm_semantics(model):
    """(Semantics of robot_description_semantic, velocity and acceleration limits of
    robot_description_planning) for model."""
    try:
        semantics = read_srdf(str(_param(SEMANTIC)), model)
    except ModelError as error:
        _fail('%s: %s' % (rospy.resolve_name(SEMANTIC), error))
    limits = _param(PLANNING)
    try:
        return semantics, read_velocity_limits(limits, model), \
            read_acceleration_limits(limits, model)
    except ModelError as error:
        _fail('%s: %s' % (rospy.resolve_name(PLANNING), error))


def stop_acceleration(model):
    """The acceleration limits [rad/s^2] the arm brakes within when stopped: those of
    robot_description_planning; where it is not set (a controller started without the
    planning parameters), inf, stopping the arm at once, with a warning saying so."""
    if not rospy.has_param(PLANNING):
        rospy.logwarn('%s: no %s: no acceleration limits to brake within, so a stop holds the '
                      'arm at once where it is', rospy.get_name(), rospy.resolve_name(PLANNING))
        return np.full(len(model.names), np.inf)
    try:
        return read_acceleration_limits(rospy.get_param(PLANNING), model)
    except ModelError as error:
        _fail('%s: %s' % (rospy.resolve_name(PLANNING), error))
