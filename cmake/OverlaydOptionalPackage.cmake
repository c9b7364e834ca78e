# SPDX-License-Identifier: Apache-2.0
# overlayd_optional_package(OPTION PREFIX MODULE DOC): a cache option AUTO | ON | OFF for a pkg-config dependency that
# a feature can be built without (AUTO: when found; ON: required; OFF: never). Sets PREFIX_FOUND and the imported
# target PkgConfig::PREFIX as pkg_check_modules does.
function(overlayd_optional_package option prefix module doc)
    set(${option} AUTO CACHE STRING "${doc} (AUTO: when ${module} is found, ON, OFF)")
    set_property(CACHE ${option} PROPERTY STRINGS AUTO ON OFF)
    set(${prefix}_FOUND FALSE)
    if(${option} STREQUAL "ON")
        pkg_check_modules(${prefix} REQUIRED IMPORTED_TARGET GLOBAL ${module})
    elseif(${option} STREQUAL "AUTO")
        pkg_check_modules(${prefix} IMPORTED_TARGET GLOBAL ${module})
    endif()
    set(${prefix}_FOUND ${${prefix}_FOUND} PARENT_SCOPE)
    set(${prefix}_VERSION ${${prefix}_VERSION} PARENT_SCOPE)
endfunction()
