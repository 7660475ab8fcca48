"""`grade --task line`: a line follower (the lab's experiment 5) graded on generated line courses.

What a case of the line task is, for grader.CaseRunner: its course
(worlds/line_courses.py, from --seed and the case's number, --room the
size of a loop), the world written for it into OUT/worlds/ (with the course
file the case is scored against beside it), and its harness,
launch/line_case.launch: the simulator and nodes/evaluation/line_case.py,
which writes the case's ground-truth record (line_record.py), graded by
line_criteria.py. The solution's launch file starts its line follower only,
as the course task's starts its course nodes; it sees a TurtleBot3 Waffle's
interface: `image` and `camera_info` of the course's camera, its tf,
`odom`, `cmd_vel`.
"""
import os

import rospkg

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.evaluation.scoring.line import speed_bound
from wall_follower.evaluation.scoring.line_track import centreline_of
from wall_follower.evaluation.worlds.line_courses import (DEFAULT_ROOM, course_name,
                                                          generate_line, write_line_world)

# Simulated seconds a case may last without a lap (or a stop): a start, then two runs of
# the line at its speed bound.
TIME_ALLOWANCE = (30.0, 2.0)
# Wall seconds a lockstep step waits for the solution's command: a camera frame rendered
# and read on a busy machine (as line_follow.test gives line_follower), so that load
# cannot change a result.
LOCKSTEP_TIMEOUT = 10.0


def time_limit(line_course):
    """Simulated seconds a case on line_course may last (see TIME_ALLOWANCE)."""
    centreline = centreline_of(line_course.course)
    return TIME_ALLOWANCE[0] + TIME_ALLOWANCE[1] * centreline.length / speed_bound(
        centreline, MAX_LINEAR, MAX_ANGULAR)


class LineTask(object):
    """The line task's cases, for grader.CaseRunner (the course task's: grader.CourseTask)."""

    name = 'line'
    launch_file = 'line_case.launch'
    default_room = DEFAULT_ROOM

    def __init__(self, seed, room, out):
        self.seed = seed
        self.room = tuple(room)
        self.out = out

    def generate(self, index):
        return generate_line(self.seed, index, self.room)

    def case_name(self, index):
        return course_name(self.seed, index)

    def write(self, line_course, index):
        """Write the case's world, bitmap and course file into OUT/worlds/; the world's path."""
        worlds = os.path.join(rospkg.RosPack().get_path('wall_follower'), 'worlds')
        return write_line_world(line_course, os.path.join(self.out, 'worlds'), worlds,
                                self.seed, index)

    def case_args(self, line_course):
        """line_case.launch's arguments of the task's own (beside the harness's common ones)."""
        return {'time_limit': '%.0f' % time_limit(line_course),
                'lockstep_timeout': '%g' % LOCKSTEP_TIMEOUT}

    def notes(self):
        """What a case record of the task notes of how it ran (the course file has the rest)."""
        return {}
