# Frame-capture tests for ctest, usable by any project. Installed with the CMake package
# (find_package(Glass) includes it), or from a checkout:
#
#   find_package(Glass REQUIRED)      # or include(path/to/glass/cmake/GlassCapture.cmake)
#   glass_add_capture_case(my_character ${CMAKE_CURRENT_SOURCE_DIR}/cases/my_character.json
#                          [ARGS --plugin $<TARGET_FILE:my_plugin> --set strength=0.5 ...])
#
# Each case runs `glass-capture --case FILE --out <build dir>/capture [ARGS...]`: exit 0 on a
# match with the goldens beside FILE, 1 on a mismatch (the .actual.png, .diff.png and report
# land in the build dir), 77 (ctest: skipped) when the case's model is absent and it says
# skip_if_missing. glass-capture is this build's target if there is one, else the installed
# Glass::glass-capture, else GLASS_CAPTURE_EXECUTABLE, else the PATH's. To regenerate goldens:
# glass-capture --case FILE --update (and look at them before committing).
function(glass_add_capture_case name case_file)
    cmake_parse_arguments(PARSE_ARGV 2 arg "" "" "ARGS")
    if(TARGET glass-capture)
        set(executable $<TARGET_FILE:glass-capture>)
    elseif(TARGET Glass::glass-capture)
        set(executable $<TARGET_FILE:Glass::glass-capture>)
    elseif(GLASS_CAPTURE_EXECUTABLE)
        set(executable ${GLASS_CAPTURE_EXECUTABLE})
    else()
        find_program(GLASS_CAPTURE_EXECUTABLE glass-capture REQUIRED)
        set(executable ${GLASS_CAPTURE_EXECUTABLE})
    endif()
    add_test(NAME capture.${name}
             COMMAND ${executable} --case ${case_file} --out ${CMAKE_CURRENT_BINARY_DIR}/capture
                     ${arg_ARGS})
    # GLASS_GL_CHECKS: every draw checks its bindings against the registry (gl/Registry.h).
    set_tests_properties(capture.${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 600 LABELS "capture;gl"
                         ENVIRONMENT GLASS_GL_CHECKS=1)
endfunction()
