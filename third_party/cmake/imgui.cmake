# Dear ImGui from Debian's libimgui-dev (scripts/deps.sh installs it). No ImGui source is copied here.
#   imgui::imgui     the core library (pkg-config "imgui": /usr/include/imgui, libimgui.a).
#   imgui::backends  the GLFW + OpenGL 3 backends, compiled from the sources the package ships under
#                    /usr/share/doc/libimgui-dev/examples/backends; only defined when GLFW is found,
#                    and only built when something links it (EXCLUDE_FROM_ALL).
include_guard(GLOBAL)
find_package(PkgConfig REQUIRED)
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
if(NOT TARGET imgui::imgui)
  add_library(imgui::imgui ALIAS PkgConfig::IMGUI)
endif()

find_path(SM_IMGUI_BACKEND_DIR imgui_impl_glfw.cpp
  PATHS /usr/share/doc/libimgui-dev/examples/backends /usr/share/imgui/backends
  NO_DEFAULT_PATH)
pkg_check_modules(GLFW3 IMPORTED_TARGET glfw3)
find_package(OpenGL COMPONENTS OpenGL)
if(SM_IMGUI_BACKEND_DIR AND GLFW3_FOUND AND TARGET OpenGL::OpenGL AND NOT TARGET imgui::backends)
  add_library(sm_imgui_backends STATIC EXCLUDE_FROM_ALL
    ${SM_IMGUI_BACKEND_DIR}/imgui_impl_glfw.cpp ${SM_IMGUI_BACKEND_DIR}/imgui_impl_opengl3.cpp)
  # Third-party code: our warning flags are not its business.
  target_compile_options(sm_imgui_backends PRIVATE -w)
  target_include_directories(sm_imgui_backends SYSTEM PUBLIC /usr/include/imgui/backends)
  target_link_libraries(sm_imgui_backends PUBLIC imgui::imgui PkgConfig::GLFW3 OpenGL::OpenGL ${CMAKE_DL_LIBS})
  add_library(imgui::backends ALIAS sm_imgui_backends)
endif()
