"""Parameters of the wall_following node: the node's own, then the follower's.

Distances are the laser's, to the wall, in metres, unless said otherwise.
"""
import math

from wall_follower.params import Parameter as P, Section, driving

BLIND_TURN = 0.3
"""How fast [rad/s] the follower turns toward its wall, on the right, while its laser shows
nothing ahead: ~blind_turn's default is this turn to the right."""

NODE = (
    driving.loop(scan_timeout=0.5, blind_turn=-BLIND_TURN),
    driving.LIMITS,
    Section('node', (
        P('find_wall', True, 'call the find_wall service first; do not follow if it fails '
          '(read at start)'),
        P('record_odom', True, 'send a goal to the record_odom action before following '
          '(read at start)'),
        P('stop_after_lap', True, 'when record_odom reports the lap: stop the robot and end the '
          'node'),
        P('service_wait', 30.0, 'wait this long for find_wall and record_odom to appear '
          '[wall s] (read at start)', 0.0, 600.0),
        P('feedback_period', 5.0, 'log the distance record_odom reports at most this often [s]',
          0.0, 600.0),
    )),
)
"""The node's own parameters (wall_follower.nodes.course.wall_following)."""

FOLLOWER = (
    Section('robot', (
        P('laser_x', -0.032, 'laser position ahead of the rotation centre [m] (a Burger has it '
          'behind; a Waffle twice as far behind)', -0.3, 0.3),
        P('body_rear', 0.101, "how far the robot's body reaches behind the rotation centre [m] "
          '(a Burger; config/waffle_pi.yaml has a Waffle)', 0.0, 1.0),
        P('body_half_width', 0.089, "half the width of the robot's body [m]", 0.0, 1.0),
        P('body_clearance', 0.04, 'before a left turn, ride no nearer the wall than keeps the '
          "body's tail this far from it as the turn swings it round [m]", 0.0, 0.5),
    )),
    Section('straight_wall', (
        P('target_distance', 0.25, 'wanted distance to the wall on the right [m]', 0.12, 1.0),
        P('range_bias', 0.008, 'how much longer than true the laser reads [m] (Stage, with its '
          'grid, reads long; an ideal laser wants 0)', -0.05, 0.05),
        P('cruise_speed', 0.19, 'forward speed on a straight wall [m/s]', 0.0, 0.19),
        P('max_turn_rate', 0.49, 'largest turn rate the controller asks for [rad/s]', 0.01, 0.49),
        P('k_distance', 11.0, 'turn rate per metre of distance error [1/s]', 0.0, 100.0),
        P('k_angle', 3.0, 'turn rate per radian of heading into the wall [1/s]', 0.0, 100.0),
        P('latency', 0.1, 'scan-to-motion delay: each scan is judged where the robot will be '
          'by then [s]', 0.0, 1.0),
        P('turn_slowdown', 0.0, 'share of cruise speed given up at the largest turn rate',
          0.0, 1.0),
        P('closest_distance', 0.215, 'heading into the wall, slow down so as to turn parallel '
          'no nearer than this; turning left onto a wall ahead, pass nothing else on the right '
          'nearer than this [m]', 0.0, 1.0),
        P('farthest_distance', 0.285, 'heading away from the wall, slow down so as to turn '
          'parallel no farther than this; farther off, dive onto it [m]', 0.0, 2.0),
        P('min_arc_radius', 0.2, '... (either way) but never onto an arc tighter than this [m]',
          0.0, 1.0),
    )),
    Section('wall_fit', (
        P('wall_sector', math.radians(60.0), 'half width of the sector around the right '
          'searched for the wall [rad]', 0.0, math.pi),
        P('wall_seed_ahead', math.radians(35.0), 'the sector from straight right to this far '
          'ahead of it seeds the wall fit [rad] ...', 0.0, math.pi / 2),
        P('wall_seed', math.radians(20.0), '... and where that holds no wall running on at '
          'least rejoin_ahead ahead, the sector this far either side of straight right '
          '[rad]', 0.0, math.pi),
        P('wall_fit_range', 0.8, 'hits farther than this are not taken for the wall on the '
          'right [m]', 0.1, 5.0),
        P('wall_inlier_distance', 0.025, 'hits this near the seed line belong to the wall [m]',
          0.001, 0.5),
        P('wall_min_points', 6, 'fewest hits that make a wall', 2, 1000),
        P('wall_max_residual', 0.025, 'RMS misfit above which the hits are no straight wall [m]',
          0.001, 0.5),
        P('wall_seed_support', 0.6, 'share of the seed hits the final wall line must still pass '
          'through', 0.0, 1.0),
        P('wall_continue_gap', 0.06, 'the wall runs on past its fitted line over hits this near '
          'the one before [m] ...', 0.0, 1.0),
        P('wall_continue_angle', math.radians(15.0), '... that bend away from the line by no '
          'more than this [rad]', 0.0, math.pi / 2),
        P('wall_lost_distance', 0.45, 'a wall farther than this is not followed (outer corner, '
          'or no wall) [m]', 0.1, 5.0),
    )),
    Section('inner_corner', (
        P('corridor_half_width', 0.14, 'half width of the lane ahead searched for a wall ahead '
          '[m]', 0.0, 1.0),
        P('ahead_range', 1.0, 'walls ahead are looked for up to this far [m]', 0.1, 5.0),
        P('ahead_min_angle', math.radians(30.0), 'a wall ahead must cross the heading at least '
          'this steeply [rad]', 0.0, math.pi / 2),
        P('wide_start', math.radians(30.0), 'the first part of the left turn onto a wall ahead, '
          'flown at cruise speed on its widest arc [rad]; 0 for none', 0.0, math.pi / 2),
        P('inner_corner_radius', 0.09, '... then the turn goes on at this radius past the '
          'corner [m] ...', 0.0, 1.0),
        P('wide_end', math.radians(32.0), '... and flies its last part at cruise speed again '
          '[rad]; 0 for none. Much more than 32 degrees, and it begins where the laser reads the '
          'new wall beyond the band', 0.0, math.pi / 2),
        P('wide_allowance', 0.015, 'the wide start may carry the robot this far past '
          'target_distance [m]; it rides nearer by the rest of the drift first', 0.0, 0.5),
        P('short_turn_cut', math.radians(5.0), 'a wide start cut by more than this (no room to '
          'ride nearer first): fly the short-wall turn [rad]', 0.0, math.pi / 2),
        P('short_turn_radius', 0.16, 'the short-wall turn: this radius past the corner [m] ...',
          0.0, 1.0),
        P('short_wide_start', math.radians(20.0), '... after this much of it at cruise speed '
          '[rad] ...', 0.0, math.pi / 2),
        P('short_wide_end', math.radians(25.0), '... and before this much again [rad]',
          0.0, math.pi / 2),
        P('turn_farthest', 0.30, 'tighten the left turn\'s tight arc until its plan, flown '
          'through an ideal corner, keeps the wall on the right reading no farther than this, '
          'as the course reads it (the nearest range within right_sector of the right) [m] ...',
          0.0, 5.0),
        P('turn_tolerance', 0.01, '... where the plan would read more than this farther: at '
          'the hand-over to its wide end, a turn begun after riding nearer reads about 0.30 m, '
          'one begun without room to up to 0.31 m, one begun at the band\'s far edge 0.32-0.33 '
          'm. Lower tightens more turns, at a cost in lap time [m]', 0.0, 1.0),
        P('right_sector', math.radians(30.0), '... where right_sector is half the width of '
          'the sector round the right that the course reads [rad]', 0.0, math.pi / 2),
        P('approach_range', 0.8, 'with a wall ahead this near, ride nearer the wall by the '
          'drift of the wide start less wide_allowance [m]', 0.0, 5.0),
        P('landing_run', 0.45, 'the left turn lands inner_corner_distance from the new wall '
          'only where that runs on at least this far ahead; on a shorter one it lands at '
          'target_distance, from which the turn round its end is planned, or where the turn '
          'flown as planned lands, if that is nearer (but no nearer than '
          'inner_corner_distance) [m]', 0.0, 5.0),
        P('inner_corner_distance', 0.22, 'distance of the rotation centre from the wall ahead '
          'at which the left turn ends [m]', 0.05, 1.0),
        P('turn_lead', 0.02, 'start the left turn this much early, for the scan and command '
          'delay; what the turn then has to spare, its wide end flies [m]', -0.5, 0.5),
        P('settle_time', 3.0, 'after the left turn (which lands nearer than target_distance on '
          'purpose), raise the distance gain for this long [s] ...', 0.0, 60.0),
        P('settle_gain', 1.5, '... by this factor, to come back out to target_distance sooner',
          0.0, 10.0),
        P('rejoin_behind', math.radians(15.0), 'a left turn ends only on a wall turned at '
          'most this far away on the right: the wall it leaves lies ever farther behind [rad]',
          0.0, math.pi / 2),
        P('front_turn_distance', 0.38, 'anything nearer than this in the lane ahead starts the '
          'left turn [m]', 0.0, 5.0),
        P('front_clear_distance', 0.6, 'the left turn goes on while anything in the lane ahead '
          'is nearer [m]', 0.0, 5.0),
        P('clear_margin', 0.06, 'a left turn ends only once the lane ahead, this much wider on '
          'each side, is clear to front_turn_distance, or holds nothing but the wall the turn '
          'leaves, turned more than rejoin_behind away from, or the wall it has come round '
          'parallel to, read no more than this nearer than its line; and with a wall across '
          'the way, what stands out of the right wall by more than this, nearer than that '
          'wall, is kept off [m]', 0.0, 1.0),
        P('front_stop_distance', 0.2, 'anything nearer than this in the lane ahead: turn on the '
          'spot [m]', 0.0, 5.0),
    )),
    Section('outer_corner', (
        P('outer_corner_radius', 0.25, 'radius of the arc round the tip of an outer corner, '
          'between its wide arcs [m]', 0.0, 1.0),
        P('outer_wide_start', math.radians(45.0), 'the first part of that turn, flown at cruise '
          'speed on its widest arc [rad] ...', 0.0, math.pi / 2),
        P('outer_wide_end', math.radians(45.0), '... and the last, begun where it ends '
          'outer_corner_offset past target_distance from the next wall [rad]', 0.0, math.pi / 2),
        P('outer_corner_offset', 0.015, 'that turn is planned as if it began and ended this much '
          'farther than target_distance from the walls: its arcs pass the tip that much farther '
          'out [m]', -0.1, 0.1),
        P('outer_turn_lead', -0.005, 'start the turn round the end of a wall this much early '
          '(negative: late) [m]', -0.5, 0.5),
        P('outer_wide_tolerance', 0.03, 'the wide start is flown even this far inside the arc '
          'round the tip (the tip is seen to a grid cell or so) [m]', 0.0, 0.5),
        P('circling_speed_share', 0.9, 'a corner with no wall to pin an arc to is circled at '
          'this share of target_distance times max_turn_rate (turn headroom)', 0.0, 1.0),
        P('corner_gate', 0.1, 'the tip of a corner is looked for this near where it is expected, '
          'and no farther than this along the wall that ended from where it was first seen [m]',
          0.0, 1.0),
        P('corner_bearing', math.radians(30.0), 'after a left turn, circle the end of a wall '
          'only if this near the right, or farther behind it with no wall along the right '
          '[rad]', 0.0, math.pi),
        P('rejoin_ahead', 0.15, 'after a corner, follow a wall seen at least this far ahead [m] '
          '...', 0.0, 5.0),
        P('rejoin_angle', math.radians(40.0), '... and within this angle of the heading [rad]',
          0.0, math.pi / 2),
        P('arc_exit_angle', math.radians(5.0), 'an outer corner arc ends this near parallel to '
          'the next wall [rad]', 0.0, math.pi / 2),
    )),
    Section('pillar', (
        P('pillar_window', 0.3, 'a round pillar is fitted to the hits on the right this near the '
          'nearest one [m] ...', 0.05, 1.0),
        P('pillar_clearance', 0.15, '... when no hit lies up to this much farther from it (the '
          'pillar stands free) [m] ...', 0.0, 1.0),
        P('pillar_max_radius', 0.25, '... and its circle is no larger than this [m] ...', 0.0,
          1.0),
        P('pillar_fit_tolerance', 0.02, '... and fits those hits this well, RMS [m]; it is '
          'circled while it does ...', 0.0, 0.1),
        P('pillar_min_arc', math.radians(100.0), '... once, on pillar_confirm scans running, '
          'those hits span this much of it [rad] ...', 0.0, 2.0 * math.pi),
        P('pillar_max_bulge', 0.02, "... and bend from it by no more than this (a small box's "
          'corner bends them by more) [m] ...', 0.0, 0.1),
        P('pillar_confirm', 3, '... see pillar_min_arc [scans]', 1, 100),
        P('pillar_nearer', 0.015, 'circle a round pillar this much nearer than target_distance '
          "[m] (Stage's grid draws a small disc up to a cell fatter on one side)", 0.0, 0.1),
    )),
    Section('search', (
        P('search_speed', 0.15, 'no wall near: drive straight at this speed until one appears '
          '[m/s]', 0.0, 0.19),
    )),
)
"""The follower's parameters (wall_follower.control.following.follower.FollowerParams)."""

TABLE = NODE + FOLLOWER
