"""Parameters of the camera_view node (the lab's first steps: the camera's frames, looked at)."""
from wall_follower.params import Parameter as P, Section
from wall_follower.params.camera.line_mask import IMAGE

NODE = (
    Section('view', (
        P('report_period', 5.0, 'log the frames\' size, encoding and rate this often [s]',
          0.1, 3600.0),
        P('window', True, 'show the frames in a window when a display is there'),
        P('snapshot_dir', '', 'without a window, write PNG snapshots into this directory, made '
          "if missing ('': none)"),
        P('snapshot_period', 2.0, 'write a snapshot this often [s]', 0.1, 3600.0),
    )),
)

TABLE = IMAGE + NODE
