"""Generated worlds written for the closed-loop tests (shared by the unit tests, not itself a
test module): a world of the generator's, with the shipped Burger."""
import os

from wall_follower.evaluation.worlds import generator

BURGER = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds', 'burger.inc')


def write_generated(directory, seed, index, start=None):
    """The generator's world index of seed, written into directory, its start moved to start
    (x, y, yaw) when given: (the world file's path, the world)."""
    world = generator.generate(seed, index)
    if start is not None:
        world = world._replace(start=start)
    return generator.write_world(world, str(directory), BURGER, seed, index), world
