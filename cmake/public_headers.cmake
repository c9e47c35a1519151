# A library's public headers: what other folders of the project may include. Every other
# header of the library's folder is internal to it (tests may still include it: they test the
# library from inside, as Box2D's tests do). `make test` checks the rule
# (tests/layers/check_public_headers.cmake); a new include of an internal header from another
# folder fails it with the file, the line and the header.
#
#   arena_public_headers(FOLDER server/net HEADERS tcp_transport.hpp udp_transport.hpp)
#
# FOLDER is relative to the project root; HEADERS are relative to FOLDER, and GENERATED names
# headers the build writes there (flatc's). A folder may be
# named by several calls (two libraries in one folder): its public headers are their union.
function(arena_public_headers)
  cmake_parse_arguments(ARG "" "FOLDER" "HEADERS;GENERATED" ${ARGN})
  if(NOT ARG_FOLDER OR NOT ARG_HEADERS)
    message(FATAL_ERROR "arena_public_headers: FOLDER and HEADERS are needed")
  endif()
  foreach(header IN LISTS ARG_HEADERS)
    if(NOT EXISTS "${PROJECT_SOURCE_DIR}/${ARG_FOLDER}/${header}")
      message(FATAL_ERROR "arena_public_headers: ${ARG_FOLDER}/${header} does not exist")
    endif()
  endforeach()
  list(JOIN ARG_HEADERS " " headers)
  if(ARG_GENERATED)
    list(JOIN ARG_GENERATED " " generated)
    string(APPEND headers " ${generated}")
  endif()
  set_property(GLOBAL APPEND PROPERTY ARENA_PUBLIC_HEADERS "${ARG_FOLDER}: ${headers}")
endfunction()

# Writes every declaration, one folder a line ("FOLDER: a.hpp b.hpp"), for the check.
function(arena_write_public_headers path)
  get_property(lines GLOBAL PROPERTY ARENA_PUBLIC_HEADERS)
  list(JOIN lines "\n" text)
  file(WRITE "${path}" "${text}\n")
endfunction()
