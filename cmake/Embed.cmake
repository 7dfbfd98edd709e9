# ranryu_embed(TARGET name ROOT dir NAMESPACE ns GLOBS ... [EXCLUDE regex]): a static library holding
# every matching file under ROOT (less those whose path matches EXCLUDE) as ns::kEmbeddedFiles (see
# engine/core/embedded.h).
function(ranryu_embed)
  cmake_parse_arguments(E "" "TARGET;ROOT;NAMESPACE;EXCLUDE" "GLOBS" ${ARGN})
  set(_globs "")
  foreach(g IN LISTS E_GLOBS)
    list(APPEND _globs ${E_ROOT}/${g})
  endforeach()
  file(GLOB_RECURSE _files CONFIGURE_DEPENDS RELATIVE ${E_ROOT} ${_globs})
  if(E_EXCLUDE)
    list(FILTER _files EXCLUDE REGEX "${E_EXCLUDE}")
  endif()
  list(SORT _files)
  set(_abs "")
  foreach(f IN LISTS _files)
    list(APPEND _abs ${E_ROOT}/${f})
  endforeach()
  set(_out ${CMAKE_CURRENT_BINARY_DIR}/${E_TARGET}.cpp)
  add_custom_command(
    OUTPUT ${_out}
    COMMAND ${CMAKE_COMMAND} -DROOT=${E_ROOT} "-DFILES=${_files}" -DNAMESPACE=${E_NAMESPACE}
            -DOUT=${_out} -P ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    DEPENDS ${_abs} ${PROJECT_SOURCE_DIR}/cmake/EmbedFiles.cmake
    COMMENT "Embedding ${E_ROOT}"
    VERBATIM)
  add_library(${E_TARGET} STATIC ${_out})
  target_include_directories(${E_TARGET} PRIVATE ${PROJECT_SOURCE_DIR}/engine)
endfunction()
