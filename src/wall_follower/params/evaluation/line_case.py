"""Parameters of the line_case node (one graded line-following run), read once at start.

No dynamic_reconfigure server: like grade_case, the node watches one run
and ends. Its limits are grade_case's own (the grader checks --start-limit
against one range for both tasks); `still` is the line task's.
"""
from wall_follower.params import Parameter as P, Section, parameters
from wall_follower.params.evaluation.grade_case import TABLE as COURSE_CASE


def _course_case(name):
    return next(p for p in parameters(COURSE_CASE) if p.name == name)


TABLE = (
    Section('case', (
        P('world', '', 'the generated line .world file the run is scored against (its course '
          'file NAME.course.yaml beside it)'),
        P('json', '', "file for the case's ground-truth record (the grader reads it)"),
        P('plot', '', 'PNG file for the true path over the line; empty: none'),
    )),
    Section('limits', tuple(_course_case(name) for name in (
        'start_limit', 'time_limit', 'idle_limit', 'gone_limit')) + (
        P('still', 5.0, 'simulated seconds without motion that make a stop: on an open line '
          'the run then ends (no motion after the stop for this long), on a closed one it '
          'ends without a lap [s]', 0.5, 600.0),
    )),
)
"""Every parameter of line_case."""
