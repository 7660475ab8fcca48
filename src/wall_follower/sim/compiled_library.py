"""Loading the simulator's C libraries through ctypes, and handing them numpy arrays.

catkin builds each library with the workspace (CMakeLists.txt) and puts it
on LD_LIBRARY_PATH (devel/lib, or lib of the install space) when the
workspace's setup file is sourced. The structs passed to them point into
numpy arrays, which the Python side must keep alive for the call.
"""
import ctypes

import numpy as np

# The C side's int64_t and double, and a pointer field set from a numpy array's
# address (cheaper per call than a typed pointer).
INT = ctypes.c_int64
DOUBLE = ctypes.c_double
ADDRESS = ctypes.c_void_p


def missing_message(library, needed_by, source):
    """What to tell a user whose library was not found: which, for what, and how to build it."""
    return ("%s needs %s (built from %s by catkin_make), which is not on LD_LIBRARY_PATH: "
            "run catkin_make in the catkin workspace, then source its devel/setup.bash"
            % (needed_by, library, source))


def load_function(library, name, argtypes):
    """The C function `name` of the shared `library` (no return value), None if not found."""
    try:
        function = getattr(ctypes.CDLL(library), name)
    except (OSError, AttributeError):
        return None
    function.restype = None
    function.argtypes = argtypes
    return function


def address(array, dtype):
    """`array` as the C-contiguous `dtype` array a field points into, and its address."""
    array = np.ascontiguousarray(array, dtype=dtype)
    return array, array.ctypes.data
