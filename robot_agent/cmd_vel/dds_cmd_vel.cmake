# cmd_vel for a real ROS 2 robot over CycloneDDS (see dds_cmd_vel.h).
#
# Include from robot_agent/CMakeLists.txt. Gives dtmf_dds_cmd_vel
# (`#include "cmd_vel/dds_cmd_vel.h"`); its users also get the ROS 2 types and DDS helpers of
# common/ros2 (`#include "ros2/ros2_msgs.h"`) and CycloneDDS, as a test subscriber needs them.
cmake_path(GET CMAKE_CURRENT_LIST_DIR PARENT_PATH _dtmf_robot_agent_dir)
add_library(dtmf_dds_cmd_vel STATIC ${CMAKE_CURRENT_LIST_DIR}/dds_cmd_vel.cpp)
target_include_directories(dtmf_dds_cmd_vel PUBLIC ${_dtmf_robot_agent_dir})
target_link_libraries(dtmf_dds_cmd_vel PUBLIC dtmf_ros2)
