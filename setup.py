"""Python package of wall_follower, installed by catkin_python_setup()."""
from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(
    packages=['wall_follower', 'wall_follower.control', 'wall_follower.sim', 'wall_follower.nodes',
              'wall_follower.evaluation', 'wall_follower.exercises',
              'wall_follower.evaluation.benchmarks'],
    package_dir={'': 'src'},
))
