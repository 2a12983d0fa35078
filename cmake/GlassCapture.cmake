# Frame-capture tests for ctest, usable by any project:
#
#   include(path/to/glass/cmake/GlassCapture.cmake)
#   glass_add_capture_case(my_character ${CMAKE_CURRENT_SOURCE_DIR}/cases/my_character.json)
#
# Each case runs `glass-capture --case FILE --out <build dir>/capture`: exit 0 on a match with
# the goldens beside FILE, 1 on a mismatch (the .actual.png, .diff.png and report land in the
# build dir), 77 (ctest: skipped) when the case's model is absent and it says skip_if_missing.
# glass-capture comes from this build's target if present, else GLASS_CAPTURE_EXECUTABLE, else
# the PATH. To regenerate goldens: glass-capture --case FILE --update (and look at them).
function(glass_add_capture_case name case_file)
    if(TARGET glass-capture)
        set(executable $<TARGET_FILE:glass-capture>)
    elseif(GLASS_CAPTURE_EXECUTABLE)
        set(executable ${GLASS_CAPTURE_EXECUTABLE})
    else()
        find_program(executable glass-capture REQUIRED)
    endif()
    add_test(NAME capture.${name}
             COMMAND ${executable} --case ${case_file} --out ${CMAKE_CURRENT_BINARY_DIR}/capture)
    set_tests_properties(capture.${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 LABELS "capture;gl")
endfunction()
