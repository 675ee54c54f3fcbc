# ROS 2 on this machine only, to drive the robots through dtmf-ros-bridge, which listens on
# loopback (docs/ros.md). Source it in the shell that runs the ROS 2 tools:
#   source /usr/share/dtmf-teleop/ros/localhost.sh     (from the sources: clients/ros_bridge/ros/)
#   ros2 run teleop_twist_keyboard teleop_twist_keyboard --ros-args -p repeat_rate:=10.0
# Both of ROS 2 Jazzy's middlewares are set to loopback: Fast DDS (the default) and CycloneDDS
# (RMW_IMPLEMENTATION=rmw_cyclonedds_cpp). A ROS 2 node set so reaches no other machine.
dtmf_ros_dir=$(cd "$(dirname "${BASH_SOURCE[0]:-$0}")" && pwd)
export FASTRTPS_DEFAULT_PROFILES_FILE=$dtmf_ros_dir/fastdds-localhost.xml
export CYCLONEDDS_URI=file://$dtmf_ros_dir/cyclonedds-localhost.xml
unset dtmf_ros_dir
