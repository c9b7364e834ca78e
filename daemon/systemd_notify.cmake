# SPDX-License-Identifier: Apache-2.0
# daemon/systemd_notify.cmake: the SystemdNotifier library (overlayd::systemd_notify), with libsystemd or without.
# include() it from daemon/CMakeLists.txt and link overlayd::systemd_notify; tests/systemd includes it too when the
# daemon does not, so the guard keeps one definition.
include_guard(GLOBAL)

set(OVERLAYD_SYSTEMD AUTO CACHE STRING "sd_notify readiness/watchdog support through libsystemd (AUTO, ON, OFF)")
set_property(CACHE OVERLAYD_SYSTEMD PROPERTY STRINGS AUTO ON OFF)

set(overlayd_have_libsystemd 0)
if(NOT OVERLAYD_SYSTEMD STREQUAL "OFF")
    find_package(PkgConfig REQUIRED)
    if(OVERLAYD_SYSTEMD STREQUAL "ON")
        pkg_check_modules(libsystemd REQUIRED IMPORTED_TARGET libsystemd)
    else()
        pkg_check_modules(libsystemd IMPORTED_TARGET libsystemd)
    endif()
    if(libsystemd_FOUND)
        set(overlayd_have_libsystemd 1)
    endif()
endif()
include(FeatureSummary)
add_feature_info(systemd-notify overlayd_have_libsystemd "READY=1, STATUS= and the watchdog (OVERLAYD_SYSTEMD; libsystemd)")
message(STATUS "overlayd: systemd notify support: ${overlayd_have_libsystemd} (OVERLAYD_SYSTEMD=${OVERLAYD_SYSTEMD})")

add_library(overlayd_systemd_notify STATIC ${CMAKE_CURRENT_LIST_DIR}/systemd_notify.cpp)
add_library(overlayd::systemd_notify ALIAS overlayd_systemd_notify)
target_include_directories(overlayd_systemd_notify PUBLIC ${PROJECT_SOURCE_DIR})
target_compile_definitions(overlayd_systemd_notify PRIVATE OVERLAYD_HAVE_LIBSYSTEMD=${overlayd_have_libsystemd})
# Consumers (tests) may ask whether real notifications are compiled in.
set_property(TARGET overlayd_systemd_notify PROPERTY OVERLAYD_HAVE_LIBSYSTEMD ${overlayd_have_libsystemd})
if(overlayd_have_libsystemd)
    target_link_libraries(overlayd_systemd_notify PRIVATE PkgConfig::libsystemd)
endif()
overlayd_warnings(overlayd_systemd_notify)
