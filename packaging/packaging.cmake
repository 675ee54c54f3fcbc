# Debian packages, one per install component (scripts/package builds them):
#
#   dtmf-teleop-agent   dtmf-agent, its systemd unit and /etc/default/dtmf-agent
#   dtmf-teleop-server  dtmf-server, dtmf-migrate, the migrations, its unit and defaults;
#                       dtmf-console (the web console), its page, unit and defaults; and
#                       dtmf-ros-bridge (ROS 2's cmd_vel in, over DDS), its unit and defaults
#   dtmf-teleop-cli     dtmfctl and dtmf-room
#
# CPack's DEB generator with dpkg-shlibdeps: each package's Depends are the libraries its
# programs link, as the installed system's shlibs files name them, never typed here. Each
# package carries the Debian copyright and changelog, a manual page per program (help2man,
# from --help and --version) and its /etc/default file as a conffile.
# Include from the top-level CMakeLists.txt after every install() rule.

set(DTMF_PACKAGING_DIR ${CMAKE_CURRENT_LIST_DIR})
set(DTMF_PACKAGE_MAINTAINER "dtmf-teleop maintainers <maintainers@users.noreply.h-seed-3dec34c7.example>")

# Which programs each component installs, for the manual pages.
set(DTMF_COMPONENT_PROGRAMS_agent dtmf-agent)
set(DTMF_COMPONENT_PROGRAMS_server dtmf-server dtmf-migrate)
if(DTMF_BUILD_CONSOLE)
  list(APPEND DTMF_COMPONENT_PROGRAMS_server dtmf-console)
endif()
if(DTMF_BUILD_ROS_BRIDGE)
  list(APPEND DTMF_COMPONENT_PROGRAMS_server dtmf-ros-bridge)
endif()
set(DTMF_COMPONENT_PROGRAMS_cli dtmfctl)
if(DTMF_BUILD_SIMULATOR)
  list(APPEND DTMF_COMPONENT_PROGRAMS_cli dtmf-room)
endif()
set(DTMF_COMPONENT_SUMMARY_agent "robot agent: drive a TurtleBot3 by sound")
set(DTMF_COMPONENT_SUMMARY_server "sender server: robot commands as audio chords, with a gRPC API")
set(DTMF_COMPONENT_SUMMARY_cli "command-line client and offline tools of the sound link")

set(DTMF_PACKAGE_COMPONENTS)
if(DTMF_BUILD_AGENT)
  list(APPEND DTMF_PACKAGE_COMPONENTS agent)
endif()
if(DTMF_BUILD_SERVER)
  list(APPEND DTMF_PACKAGE_COMPONENTS server)
endif()
if(DTMF_BUILD_CLI)
  list(APPEND DTMF_PACKAGE_COMPONENTS cli)
endif()

# gzip -9n: Debian wants compressed documentation without a timestamp (reproducible).
find_program(GZIP_PROGRAM gzip REQUIRED)
find_program(HELP2MAN_PROGRAM help2man)
set(dtmf_changelog_gz ${CMAKE_CURRENT_BINARY_DIR}/packaging/changelog.Debian.gz)
add_custom_command(OUTPUT ${dtmf_changelog_gz}
  COMMAND ${GZIP_PROGRAM} -9nc ${DTMF_PACKAGING_DIR}/changelog > ${dtmf_changelog_gz}
  DEPENDS ${DTMF_PACKAGING_DIR}/changelog VERBATIM)
set(dtmf_packaging_outputs ${dtmf_changelog_gz})

foreach(component IN LISTS DTMF_PACKAGE_COMPONENTS)
  set(package dtmf-teleop-${component})
  install(FILES ${DTMF_PACKAGING_DIR}/copyright ${dtmf_changelog_gz}
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/doc/${package} COMPONENT ${component})
  # The exceptions lintian must accept, each with its reason (packaging/lintian/).
  configure_file(${DTMF_PACKAGING_DIR}/lintian/overrides.in ${CMAKE_CURRENT_BINARY_DIR}/packaging/lintian/${package} @ONLY)
  install(FILES ${CMAKE_CURRENT_BINARY_DIR}/packaging/lintian/${package}
          DESTINATION ${CMAKE_INSTALL_DATAROOTDIR}/lintian/overrides COMPONENT ${component})
  if(HELP2MAN_PROGRAM)
    foreach(program IN LISTS DTMF_COMPONENT_PROGRAMS_${component})
      set(page ${CMAKE_CURRENT_BINARY_DIR}/packaging/man/${program}.1.gz)
      add_custom_command(OUTPUT ${page}
        COMMAND ${HELP2MAN_PROGRAM} --no-info --no-discard-stderr --name "${DTMF_COMPONENT_SUMMARY_${component}}"
                --output ${CMAKE_CURRENT_BINARY_DIR}/packaging/man/${program}.1 $<TARGET_FILE:${program}>
        COMMAND ${GZIP_PROGRAM} -9nf ${CMAKE_CURRENT_BINARY_DIR}/packaging/man/${program}.1
        DEPENDS ${program} VERBATIM)
      list(APPEND dtmf_packaging_outputs ${page})
      install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT ${component})
    endforeach()
  endif()
endforeach()
file(MAKE_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/packaging/man)
add_custom_target(dtmf_packaging_files ALL DEPENDS ${dtmf_packaging_outputs})

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME dtmf-teleop)
set(CPACK_PACKAGE_VENDOR "dtmf-teleop")
set(CPACK_PACKAGE_CONTACT "${DTMF_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_INSTALL_PREFIX /usr)
# Install with DESTDIR and the prefix /usr, so that /etc/default files land in /etc
# (dtmf_install_default decides by the prefix).
set(CPACK_SET_DESTDIR ON)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL ${DTMF_PACKAGE_COMPONENTS})
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_RELEASE 1)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${DTMF_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://h-seed-3dec34c7.example/dtmf-teleop")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS OFF)
foreach(component IN LISTS DTMF_PACKAGE_COMPONENTS)
  string(TOUPPER ${component} c)
  set(CPACK_DEBIAN_${c}_PACKAGE_NAME dtmf-teleop-${component})
  set(CPACK_DEBIAN_${c}_PACKAGE_SECTION misc)
endforeach()
# The first line is the summary; CPack indents the rest (lines under 80 characters).
set(CPACK_COMPONENT_AGENT_DESCRIPTION "dtmf-teleop ${DTMF_COMPONENT_SUMMARY_agent}
dtmf-agent listens with the robot's microphone for command chords, checks
each frame, answers with an ACK or NACK tone and drives the wheels through
ROS 2's cmd_vel over DDS (Twist or TwistStamped). A stop guard process puts
zero on cmd_vel if the agent dies. It runs as the systemd service dtmf-agent,
configured in /etc/default/dtmf-agent, and logs every reception to PostgreSQL
when given a database.")
set(CPACK_COMPONENT_SERVER_DESCRIPTION "dtmf-teleop ${DTMF_COMPONENT_SUMMARY_server}
dtmf-server turns robot commands into multi-tone audio chords, plays them
through a loudspeaker, listens for the robot's ACK or NACK, retransmits, and
streams each frame's progress to gRPC callers (TeleopService, health,
reflection). It logs every transmission to PostgreSQL; dtmf-migrate creates
the schema. It runs as the systemd service dtmf-server, configured in
/etc/default/dtmf-server. dtmf-console serves the web console on this machine
(the air live, the robots, driving, the report) as a client of dtmf-server.
dtmf-ros-bridge drives the robots from ROS 2's cmd_vel (Twist or TwistStamped,
over DDS, from this machine only unless told otherwise) through dtmf-server,
and publishes each robot's link health on /diagnostics.")
set(CPACK_COMPONENT_CLI_DESCRIPTION "dtmf-teleop ${DTMF_COMPONENT_SUMMARY_cli}
dtmfctl drives the robot through dtmf-server (drive, turn, stop, the seed's
test sequence, reports) and works offline on audio files: encode commands to
chords, decode recordings, simulate rooms. dtmf-room filters an audio stream
through a simulated or measured room.")

# /etc/default files are the administrator's: dpkg keeps their changes on upgrade.
foreach(component IN ITEMS agent server)
  if(component IN_LIST DTMF_PACKAGE_COMPONENTS)
    string(TOUPPER ${component} c)
    set(conffiles "/etc/default/dtmf-${component}\n")
    if(component STREQUAL "server" AND DTMF_BUILD_CONSOLE)
      string(APPEND conffiles "/etc/default/dtmf-console\n")
    endif()
    if(component STREQUAL "server" AND DTMF_BUILD_ROS_BRIDGE)
      string(APPEND conffiles "/etc/default/dtmf-ros-bridge\n")
    endif()
    file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/packaging/${component}/conffiles "${conffiles}")
    set(CPACK_DEBIAN_${c}_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_BINARY_DIR}/packaging/${component}/conffiles)
  endif()
endforeach()

include(CPack)
