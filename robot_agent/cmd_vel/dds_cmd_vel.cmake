# cmd_vel for a real ROS 2 robot over CycloneDDS (see dds_cmd_vel.h).
#
# Include from robot_agent/CMakeLists.txt. The project must enable C as well as CXX:
# idlc writes C. Gives dtmf_dds_cmd_vel (`#include "cmd_vel/dds_cmd_vel.h"`); its users
# also get the generated ROS 2 types (`#include "cmd_vel/ros2_msgs.h"`) and CycloneDDS,
# as a test subscriber needs them.

find_package(CycloneDDS REQUIRED)

cmake_path(GET CMAKE_CURRENT_LIST_DIR PARENT_PATH _dtmf_robot_agent_dir)

# BASE_DIR keeps the cmd_vel/ prefix: the output is <binary dir>/cmd_vel/ros2_msgs.{c,h}.
# NO_TYPE_INFO: ROS 2's own Cyclone endpoints send no XTypes type information, so every
# ROS 2 reader matches on the type name alone; ours then does the same with any of them,
# instead of having its type object compared with theirs (whose member names differ).
idlc_generate(TARGET dtmf_ros2_msgs
  FILES ${CMAKE_CURRENT_LIST_DIR}/ros2_msgs.idl
  BASE_DIR ${_dtmf_robot_agent_dir}
  NO_TYPE_INFO)

# dtmf_ros2_msgs is an INTERFACE library carrying the generated .c as a source: linked
# PRIVATE here it is compiled once, into this library, which then provides the type
# descriptors to everyone that links it.
add_library(dtmf_dds_cmd_vel STATIC ${CMAKE_CURRENT_LIST_DIR}/dds_cmd_vel.cpp)
target_include_directories(dtmf_dds_cmd_vel PUBLIC ${_dtmf_robot_agent_dir} ${CMAKE_CURRENT_BINARY_DIR})
target_link_libraries(dtmf_dds_cmd_vel PUBLIC CycloneDDS::ddsc PRIVATE dtmf_ros2_msgs)
