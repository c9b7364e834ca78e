# SPDX-License-Identifier: Apache-2.0
# overlayd_add_gtests(TARGET PREFIX [TIMEOUT seconds]): registers a GoogleTest program with CTest.
#
# Natively every test is its own CTest (gtest_discover_tests), so one failure names itself and CTest spreads the
# tests over the cores. In a cross build the programs run under CMAKE_CROSSCOMPILING_EMULATOR (qemu-aarch64), where
# starting a process costs most of a second (the emulated loader relocating OpenCV and its libraries): there each
# program runs as OVERLAYD_TEST_SHARDS CTests, GoogleTest's own sharding (GTEST_TOTAL_SHARDS / GTEST_SHARD_INDEX)
# splitting its tests between them, and a failure is named in the shard's output.
include(GoogleTest)
set(OVERLAYD_TEST_SHARDS 4 CACHE STRING "Shards per GoogleTest program in a cross build (run under the emulator)")

function(overlayd_add_gtests target prefix)
    cmake_parse_arguments(PARSE_ARGV 2 arg "" "TIMEOUT" "")
    if(NOT CMAKE_CROSSCOMPILING)
        if(arg_TIMEOUT)
            gtest_discover_tests(${target} TEST_PREFIX "${prefix}" DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${arg_TIMEOUT})
        else()
            gtest_discover_tests(${target} TEST_PREFIX "${prefix}" DISCOVERY_TIMEOUT 60)
        endif()
        return()
    endif()
    math(EXPR last "${OVERLAYD_TEST_SHARDS} - 1")
    foreach(shard RANGE ${last})
        set(name "${prefix}${target}.shard${shard}")
        add_test(NAME ${name} COMMAND ${target} --gtest_brief=1)
        set_tests_properties(${name} PROPERTIES
            ENVIRONMENT "GTEST_TOTAL_SHARDS=${OVERLAYD_TEST_SHARDS};GTEST_SHARD_INDEX=${shard}"
            LABELS emulated TIMEOUT 1800)
    endforeach()
endfunction()
