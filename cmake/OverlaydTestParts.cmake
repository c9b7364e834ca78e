# SPDX-License-Identifier: Apache-2.0
# overlayd_resolve_test_part(OPTION PACKAGE OUT): OUT is TRUE when the part OPTION (AUTO | ON | OFF, or any CMake
# boolean) is built: AUTO when find_package(PACKAGE) finds it, ON requiring it (an error when it is missing), OFF
# never. The tests' GoogleTest and the benchmarks' Google Benchmark; the daemon alone needs neither.
function(overlayd_resolve_test_part option package out)
    set(${out} FALSE PARENT_SCOPE)
    if(${option} STREQUAL "AUTO")
        find_package(${package} QUIET)
        if(${package}_FOUND)
            set(${out} TRUE PARENT_SCOPE)
        else()
            message(STATUS "${option}=AUTO: ${package} not found, not built (scripts/test.sh passes ON and installs it)")
        endif()
    elseif(${option})
        find_package(${package} REQUIRED)
        set(${out} TRUE PARENT_SCOPE)
    endif()
endfunction()
