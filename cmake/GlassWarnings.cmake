# Warnings every project target gets: glass_warnings(target).
function(glass_warnings target)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                                             -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion)
    if(GLASS_WERROR)
        target_compile_options(${target} PRIVATE -Werror)
    endif()
endfunction()
