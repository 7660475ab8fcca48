"""The line follower's one step (vision.line_step) on frames that hold no line, frames of another
size than camera_info says, and with the lab's pixel_p controller: a stop, and what is known
ahead said with every command."""
import math

import numpy as np
import pytest

from line_course import WHITE, YELLOW, PaintedFloor, camera, run, segment
from wall_follower.control.motion import STOP, Answer
from wall_follower.params import defaults
from wall_follower.params.camera.line_follower import TABLE
from wall_follower.vision.line_pursuit import FOLLOW, SEARCH
from wall_follower.vision.line_step import LineStep

HALF_WIDTH = defaults(TABLE)['ahead_half_width']
LINE = segment((0.0, 0.0), (5.0, 0.0))


def all_yellow(step, image):
    return np.full_like(image, YELLOW)


def noise(step, image):
    return np.random.RandomState(step).randint(0, 256, image.shape).astype(np.uint8)


@pytest.mark.parametrize('spoilt', [all_yellow, noise])
def test_frames_of_no_line_stop_the_robot_where_it_is(spoilt):
    poses, commands, states = run(LINE, (0.0, 0.0, 0.0), 60,
                                  spoil=lambda step, image: spoilt(step, image)
                                  if step >= 10 else None)
    assert commands[9].linear > 0.1
    assert all(c == STOP for c in commands[10:])
    assert np.allclose(poses[11:], poses[11])
    assert set(states[10:]) == {FOLLOW}      # no search on frames that are not clear floor


def test_a_search_turns_on_clear_floor_only():
    def spoil(step, image):
        if step < 10:
            return None
        return np.full_like(image, WHITE) if step % 2 else all_yellow(step, image)
    poses, commands, states = run(LINE, (0.0, 0.0, 0.0), 60, spoil=spoil)
    searching = [i for i in range(10, 60) if states[i] == SEARCH]
    assert searching
    assert all(commands[i] == STOP for i in range(10, 60) if i % 2 == 0)
    assert any(commands[i].angular != 0.0 for i in searching if i % 2)
    assert all(c.linear == 0.0 for c in commands[searching[0]:])


def test_a_frame_of_another_size_than_camera_info_says_stops_the_robot():
    step = LineStep(defaults(TABLE))
    image = PaintedFloor(LINE).frame(camera(), (0.0, 0.0, 0.0))
    result = step.update(image, camera(width=640, image_height=480), (0.0, 0.0, 0.0),
                         HALF_WIDTH)
    assert result.answer == Answer(STOP, False)
    assert result.problem == 'the image is 320x240 but camera_info says 640x480'


def test_a_frame_of_no_line_keeps_the_path_remembered():
    step = LineStep(defaults(TABLE))
    projection = camera()
    image = PaintedFloor(LINE).frame(projection, (0.0, 0.0, 0.0))
    path = step.update(image, projection, (0.0, 0.0, 0.0), HALF_WIDTH).path
    result = step.update(all_yellow(0, image), projection, (0.0, 0.0, 0.0), HALF_WIDTH)
    assert result.answer == Answer(STOP, False) and result.problem.startswith('no line: ')
    assert np.array_equal(step.memory.path, path)


def pixel_p_answer(image):
    values = dict(defaults(TABLE), controller='pixel_p')
    return LineStep(values).update(image, camera(), None, HALF_WIDTH).answer


def test_pixel_p_knows_the_line_ahead_where_its_centroid_lies_ahead():
    projection = camera()
    answer = pixel_p_answer(PaintedFloor(LINE).frame(projection, (0.0, 0.0, 0.0)))
    assert answer.command.linear > 0.0 and answer.ahead_known
    # A line along the slice's left edge: seen, but more than 30 deg to the left.
    x, y = projection.to_floor([(6.0, 185.0)])[0]
    assert math.degrees(math.atan2(y, x)) > math.degrees(HALF_WIDTH) + 1.0
    off_side = segment((x - 0.3, y), (x + 1.0, y))
    answer = pixel_p_answer(PaintedFloor(off_side).frame(projection, (0.0, 0.0, 0.0)))
    assert answer.command.angular > 0.0 and not answer.ahead_known


@pytest.mark.parametrize('spoilt', [all_yellow, noise])
def test_pixel_p_stops_on_frames_of_no_line(spoilt):
    image = PaintedFloor(LINE).frame(camera(), (0.0, 0.0, 0.0))
    assert pixel_p_answer(spoilt(0, image)) == Answer(STOP, False)
