# Dear ImGui for the overlay (app/overlay.h): Debian's libimgui-dev (1.86) gives the core as
# libimgui.a and headers: ranryu_imgui, all that the headless `profile --overlay` needs (the panel is
# drawn by ranryu's engine/render/overlay_draw.h, not by Dear ImGui's OpenGL 3 backend, which makes a
# vertex array every frame). Its GLFW backend ships only as a source in the package's doc folder
# (examples/backends/, possibly .gz-compressed), so with the window it is copied (or decompressed)
# into the build folder at configure time and built here as ranryu_imgui_glfw.
# Sets RANRYU_HAVE_IMGUI. Required with the window; optional without it.
find_path(IMGUI_INCLUDE_DIR imgui.h PATH_SUFFIXES imgui)
find_library(IMGUI_LIBRARY imgui)
# Debian's libimgui.a takes stb_rect_pack and stb_truetype from libstb (its imgui.pc: Requires: stb).
find_library(STB_LIBRARY stb)
set(RANRYU_IMGUI_BACKENDS_DIR /usr/share/doc/libimgui-dev/examples/backends CACHE PATH
    "Folder with Dear ImGui's GLFW backend source imgui_impl_glfw.cpp (or .cpp.gz)")
set(RANRYU_HAVE_IMGUI OFF)
set(_names)
if(RANRYU_HAVE_GLFW)
  list(APPEND _names imgui_impl_glfw)
endif()
set(_have_backends ON)
foreach(name ${_names})
  if(NOT EXISTS ${RANRYU_IMGUI_BACKENDS_DIR}/${name}.cpp AND NOT EXISTS ${RANRYU_IMGUI_BACKENDS_DIR}/${name}.cpp.gz)
    set(_have_backends OFF)
  endif()
endforeach()
if(NOT IMGUI_INCLUDE_DIR OR NOT IMGUI_LIBRARY OR NOT STB_LIBRARY OR NOT _have_backends)
  if(RANRYU_HAVE_GLFW)
    message(FATAL_ERROR "Dear ImGui not found (the window's overlay needs it): run scripts/install-deps.sh "
                        "(Debian: libimgui-dev), or configure with -DRANRYU_WINDOW=OFF for a headless build")
  endif()
  message(STATUS "Dear ImGui not found: building without the overlay (ranryu profile --overlay is unavailable)")
  return()
endif()
set(RANRYU_HAVE_IMGUI ON)

set(_backends)
foreach(name ${_names})
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

add_library(ranryu_imgui INTERFACE)
target_include_directories(ranryu_imgui SYSTEM INTERFACE ${IMGUI_INCLUDE_DIR} ${IMGUI_INCLUDE_DIR}/backends)
target_link_libraries(ranryu_imgui INTERFACE ${IMGUI_LIBRARY} ${STB_LIBRARY})
if(RANRYU_HAVE_GLFW)
  list(GET _backends 0 _glfw)
  add_library(ranryu_imgui_glfw STATIC ${_glfw})
  # Not our code: its own warnings are not ours to fix.
  target_compile_options(ranryu_imgui_glfw PRIVATE -w)
  target_link_libraries(ranryu_imgui_glfw PUBLIC ranryu_imgui glfw)
endif()
