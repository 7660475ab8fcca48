"""Reader for Stage 4.x world files.

Only what a 2D wall-following simulation needs is interpreted: the world's
timing and raytrace resolution, static obstacles (bitmaps, boxes, block
polygons) with their colours, differential-drive `position` robots
carrying one ranger and at most one camera, and the window's size (real
Stage draws the camera in it).
Everything else is skipped and listed in `World.unknown_keywords`, so that a
world written for real Stage still loads. What loads but is not what its
author likely meant (a camera capped at the window's size, a camera that
no robot carries, a second camera on a robot, a pan or tilt beyond a half
turn or a quarter turn) is said in `World.warnings`. Geometry follows what real Stage
does (see Stage's blockgroup.cc / model.cc): the bounding box of a model's
blocks, or of a bitmap's black pixels, is scaled to the model's `size` and
centred on the model's pose.

A malformed file raises WorldFileError("<file>:<line>: <problem>") and never
a traceback from deep inside the parser; so does a world whose obstacles
span more cells of its `resolution` than the simulator's grid may hold
(MAX_GRID_CELLS), or whose camera would still draw more than
MAX_CAMERA_PIXELS once capped at the window, before anything that size is
allocated.
"""
from .interpreter import load_world
from .specs import (MAX_CAMERA_PIXELS, MAX_GRID_CELLS, MAX_SAMPLES, STAGE_VELOCITY_BOUNDS,
                    CameraSpec, Obstacle, RangerSpec, RobotSpec, World, WorldFileError)

__all__ = ['WorldFileError', 'World', 'Obstacle', 'RobotSpec', 'RangerSpec', 'CameraSpec',
           'load_world', 'STAGE_VELOCITY_BOUNDS', 'MAX_GRID_CELLS', 'MAX_CAMERA_PIXELS',
           'MAX_SAMPLES']
