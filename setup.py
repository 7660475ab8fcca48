"""Python package of wall_follower, installed by catkin_python_setup().

Every package under src/ is found, so that an install space (catkin_make
install, a Debian or ROS build farm package) holds the whole library, not
only the folders a list named.
"""
from setuptools import find_packages, setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(
    packages=find_packages('src'),
    package_dir={'': 'src'},
))
