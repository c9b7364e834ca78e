# SPDX-License-Identifier: Apache-2.0
# Warnings are set per target (never directory-wide) so third-party code is not affected.
function(overlayd_warnings target)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wnon-virtual-dtor)
    if(OVERLAYD_WERROR)
        target_compile_options(${target} PRIVATE -Werror)
    endif()
endfunction()
