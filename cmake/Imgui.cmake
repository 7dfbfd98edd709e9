# Dear ImGui for the window's overlay (app/overlay.h): Debian's libimgui-dev (1.86) gives the core as
# libimgui.a and headers; its GLFW and OpenGL 3 backends ship only as sources in the package's doc
# folder (examples/backends/, possibly .gz-compressed), so they are copied (or decompressed) into the
# build folder at configure time and built here as ranryu_imgui.
#
# The OpenGL 3 backend takes its entry points from GLVND's libOpenGL like the engine does
# (engine/gl/gl.h, IMGUI_IMPL_OPENGL_LOADER_CUSTOM): no second loader.
find_path(IMGUI_INCLUDE_DIR imgui.h PATH_SUFFIXES imgui)
find_library(IMGUI_LIBRARY imgui)
# Debian's libimgui.a takes stb_rect_pack and stb_truetype from libstb (its imgui.pc: Requires: stb).
find_library(STB_LIBRARY stb)
set(RANRYU_IMGUI_BACKENDS_DIR /usr/share/doc/libimgui-dev/examples/backends CACHE PATH
    "Folder with Dear ImGui's backend sources imgui_impl_glfw.cpp and imgui_impl_opengl3.cpp (or .cpp.gz)")
if(NOT IMGUI_INCLUDE_DIR OR NOT IMGUI_LIBRARY OR NOT STB_LIBRARY)
  message(FATAL_ERROR "Dear ImGui not found (the window's overlay needs it): run scripts/install-deps.sh "
                      "(Debian: libimgui-dev), or configure with -DRANRYU_WINDOW=OFF for a headless build")
endif()

set(_backends)
foreach(name imgui_impl_glfw imgui_impl_opengl3)
  set(_out ${CMAKE_BINARY_DIR}/imgui_backends/${name}.cpp)
  set(_src ${RANRYU_IMGUI_BACKENDS_DIR}/${name}.cpp)
  if(EXISTS ${_src})
    configure_file(${_src} ${_out} COPYONLY)
  elseif(EXISTS ${_src}.gz)
    find_program(GZIP_EXECUTABLE gzip REQUIRED)
    execute_process(COMMAND ${GZIP_EXECUTABLE} -dc ${_src}.gz OUTPUT_FILE ${_out} RESULT_VARIABLE _rc)
    if(NOT _rc EQUAL 0)
      message(FATAL_ERROR "cannot decompress ${_src}.gz (gzip exit ${_rc})")
    endif()
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${_src}.gz)
  else()
    message(FATAL_ERROR "Dear ImGui backend source ${_src} (or .gz) not found: install libimgui-dev "
                        "(scripts/install-deps.sh) or set RANRYU_IMGUI_BACKENDS_DIR")
  endif()
  list(APPEND _backends ${_out})
endforeach()

add_library(ranryu_imgui STATIC ${_backends})
target_include_directories(ranryu_imgui SYSTEM PUBLIC ${IMGUI_INCLUDE_DIR} ${IMGUI_INCLUDE_DIR}/backends)
target_compile_definitions(ranryu_imgui PRIVATE IMGUI_IMPL_OPENGL_LOADER_CUSTOM GL_GLEXT_PROTOTYPES=1)
# Not our code: its own warnings are not ours to fix. The system's GL core-profile header, included
# first, declares what the backend calls.
target_compile_options(ranryu_imgui PRIVATE -w -include GL/glcorearb.h)
target_link_libraries(ranryu_imgui PUBLIC ${IMGUI_LIBRARY} ${STB_LIBRARY} glfw OpenGL::OpenGL)
