# Shared by tools/run-main and tools/run-tests (sourced, not run): installs the
# Debian packages the package needs, then builds a catkin workspace outside the
# repo. Safe to run again: apt is skipped when everything is installed and
# catkin_make only rebuilds what changed.

# Debian's ROS lives under /usr; a pyenv python3 first on PATH cannot see it.
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"

REPO_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# One workspace per clone (its folder's name and a hash of its path), so that a
# workspace never links to another clone, nor to one since deleted;
# $WALL_FOLLOWER_WS names another.
CLONE_NAME="$(basename "$REPO_DIR")-$(printf '%s' "$REPO_DIR" | sha1sum | cut -c1-8)"
WS_DIR="${WALL_FOLLOWER_WS:-${XDG_CACHE_HOME:-$HOME/.cache}/wall_follower_ws/$CLONE_NAME}"

# What the build and the nodes need (the main command's list): each package is in the
# dependency table tools/dependencies.py (test/unit/test_dependencies.py checks it);
# tools/run-tests adds what only the tests need.
APT_PACKAGES="gcc g++ make cmake catkin python3-catkin-pkg python3-setuptools
  ros-message-generation ros-message-runtime python3-genpy
  python3-rospy python3-roslib python3-rospkg python3-rosgraph python3-rosgraph-msgs
  python3-roslaunch python3-rostest librostest-dev python3-actionlib
  ros-std-msgs libstd-msgs-dev python3-std-msgs
  ros-geometry-msgs libgeometry-msgs-dev python3-geometry-msgs
  ros-actionlib-msgs libactionlib-msgs-dev python3-actionlib-msgs
  ros-sensor-msgs libsensor-msgs-dev python3-sensor-msgs
  ros-nav-msgs libnav-msgs-dev python3-nav-msgs
  ros-std-srvs libstd-srvs-dev python3-std-srvs
  ros-trajectory-msgs libtrajectory-msgs-dev python3-trajectory-msgs
  python3-visualization-msgs python3-tf2-ros python3-tf2-msgs
  python3-dynamic-reconfigure libdynamic-reconfigure-config-init-mutex-dev
  python3-numpy python3-scipy python3-yaml python3-pil python3-matplotlib
  python3-opencv python3-cv-bridge
  ros-robot-state-publisher joint-state-publisher-gui liburdfdom-tools
  rosbash python3-rostopic python3-rosnode python3-rosservice python3-rosparam
  python3-rosmsg python3-rosbag
  bubblewrap"

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi
}

install_packages() {
  local missing
  # shellcheck disable=SC2086
  missing=$(dpkg-query -W -f='${db:Status-Abbrev} ${Package}\n' $APT_PACKAGES 2>&1 \
    | awk '$1 != "ii" {print $NF}')
  if [ -z "$missing" ]; then
    return 0
  fi
  echo "== installing Debian packages"
  export DEBIAN_FRONTEND=noninteractive
  as_root apt-get update -q
  # shellcheck disable=SC2086
  as_root apt-get install -y -q --no-install-recommends $APT_PACKAGES
}

build_workspace() {
  echo "== building catkin workspace in $WS_DIR"
  mkdir -p "$WS_DIR/src"
  ln -sfn "$REPO_DIR" "$WS_DIR/src/wall_follower"
  (cd "$WS_DIR" && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 \
      -DCMAKE_BUILD_TYPE=Release > "$WS_DIR/build.log" 2>&1) || {
    tail -n 40 "$WS_DIR/build.log"
    echo "catkin_make failed; full log: $WS_DIR/build.log" >&2
    return 1
  }
  # setup.bash reads unset variables, so it cannot run under set -u.
  set +u
  # shellcheck disable=SC1091
  source "$WS_DIR/devel/setup.bash"
  echo "== workspace $WS_DIR; in a shell of your own: source $WS_DIR/devel/setup.bash"
}

prepare_workspace() {
  install_packages && build_workspace
}
