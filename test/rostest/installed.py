"""Whether an optional ROS package (real Stage, gmapping) is installed, for the checks
that run only where it is."""
import rospkg


def package_installed(name):
    """True when ROS finds the package `name` on its package path."""
    try:
        rospkg.RosPack().get_path(name)
    except rospkg.ResourceNotFound:
        return False
    return True
