# The third-party libraries every build needs: Eigen, FlatBuffers (runtime headers and flatc),
# CLI11 and nlohmann-json, all from Debian.
#
# Natively they come from their CMake configs. In a cross build (cmake/aarch64-linux-gnu.cmake)
# those configs cannot be used: Debian's FlatBuffers, CLI11 and nlohmann_json targets list the
# host's /usr/include as their include directory, and an -isystem /usr/include on the compile
# line puts the host's C library headers ahead of the target's (and FlatBuffers' target also
# links the host's libflatbuffers.a). All three are header-only for what Arena uses, so a cross
# build gets INTERFACE targets of its own with the same names, whose include directory holds
# nothing but links to those libraries' header folders. flatc still runs on the host.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)

if(NOT CMAKE_CROSSCOMPILING)
  find_package(FlatBuffers 2.0.8 EXACT REQUIRED CONFIG)
  find_package(CLI11 REQUIRED CONFIG)
  find_package(nlohmann_json 3.11 REQUIRED CONFIG)
  return()
endif()

set(ARENA_HEADER_LINKS ${PROJECT_BINARY_DIR}/header_only_deps)
file(MAKE_DIRECTORY ${ARENA_HEADER_LINKS})

# arena_header_only(<target> <header inside its folder> <folder under /usr/include>)
function(arena_header_only target header folder)
  find_path(dir_${folder} ${folder}/${header} PATHS /usr/include NO_DEFAULT_PATH NO_CMAKE_FIND_ROOT_PATH)
  if(NOT dir_${folder})
    message(FATAL_ERROR "${folder}/${header} not found under /usr/include (run `make deps`)")
  endif()
  file(CREATE_LINK ${dir_${folder}}/${folder} ${ARENA_HEADER_LINKS}/${folder} SYMBOLIC)
  add_library(${target} INTERFACE IMPORTED GLOBAL)
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES ${ARENA_HEADER_LINKS})
endfunction()

arena_header_only(flatbuffers::flatbuffers flatbuffers.h flatbuffers)
arena_header_only(CLI11::CLI11 CLI.hpp CLI)
arena_header_only(nlohmann_json::nlohmann_json json.hpp nlohmann)

find_program(ARENA_FLATC flatc REQUIRED)
add_executable(flatbuffers::flatc IMPORTED GLOBAL)
set_target_properties(flatbuffers::flatc PROPERTIES IMPORTED_LOCATION ${ARENA_FLATC})
