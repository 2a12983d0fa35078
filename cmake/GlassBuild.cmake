# Build helpers: warnings every project target gets, and GLSL embedding.
function(glass_warnings target)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                                             -Wnon-virtual-dtor -Wconversion -Wno-sign-conversion)
    if(GLASS_WERROR)
        target_compile_options(${target} PRIVATE -Werror)
    endif()
endfunction()

# glass_shaders(TARGET DIR FUNCTION): embeds every *.glsl under DIR into TARGET, reachable as
# `std::span<const gl::ShaderFile> FUNCTION()`; names are paths relative to DIR.
function(glass_shaders target dir function)
    file(GLOB_RECURSE files CONFIGURE_DEPENDS "${dir}/*.glsl")
    set(out "${CMAKE_CURRENT_BINARY_DIR}/${function}.cpp")
    string(REPLACE ";" "|" packed "${files}")
    add_custom_command(OUTPUT "${out}"
        COMMAND ${CMAKE_COMMAND} "-DOUT=${out}" "-DROOT=${dir}" "-DFUNCTION=${function}"
                "-DFILES=${packed}" -P "${PROJECT_SOURCE_DIR}/cmake/EmbedShaders.cmake"
        DEPENDS ${files} "${PROJECT_SOURCE_DIR}/cmake/EmbedShaders.cmake"
        COMMENT "Embedding shaders for ${target}" VERBATIM)
    target_sources(${target} PRIVATE "${out}")
endfunction()
