# Fails when a transport reaches past the host's interface: a file of one transport in
# server/net/ that includes another transport's header, a file there that includes the host's
# class (server/host/host.hpp), or a file of the host in server/host/ that includes a transport.
# The host knows transports only as host::transport, a transport knows the host only as
# host::transport_host (server/host/transport.hpp).
#   cmake -DROOT=<source dir> -P check_transports.cmake
if(NOT ROOT)
  message(FATAL_ERROR "check_transports: pass -DROOT=...")
endif()

# Each transport's files, by the start of their names in server/net/ (what is in none of them,
# bounded_output, is shared by the stream transports).
set(transports "tcp|tcp_transport|session" "udp|udp_|enet_wire" "web|web_transport|ws_session|static_files")

function(transport_of name out)
  set(found "")
  foreach(t IN LISTS transports)
    string(REPLACE "|" ";" parts "${t}")
    list(POP_FRONT parts label)
    foreach(prefix IN LISTS parts)
      if(name MATCHES "^${prefix}")
        set(found "${label}")
      endif()
    endforeach()
  endforeach()
  set(${out} "${found}" PARENT_SCOPE)
endfunction()

set(violations "")
file(GLOB net_files "${ROOT}/server/net/*.cpp" "${ROOT}/server/net/*.hpp")
file(GLOB host_files "${ROOT}/server/host/*.cpp" "${ROOT}/server/host/*.hpp")
foreach(file IN LISTS net_files host_files)
  get_filename_component(name "${file}" NAME)
  get_filename_component(dir "${file}" DIRECTORY)
  get_filename_component(dir "${dir}" NAME)
  transport_of("${name}" mine)
  file(STRINGS "${file}" includes REGEX "^#[ \t]*include[ \t]*\"server/(net|host)/")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^#[ \t]*include[ \t]*\"server/([a-z]+)/([^\"]+)\".*$" "\\1;\\2" target "${line}")
    list(GET target 0 target_dir)
    list(GET target 1 target_name)
    file(RELATIVE_PATH where "${ROOT}" "${file}")
    if(dir STREQUAL "host" AND target_dir STREQUAL "net")
      string(APPEND violations "${where}: the host includes a transport: ${line}\n")
    elseif(dir STREQUAL "net" AND target_dir STREQUAL "host" AND target_name STREQUAL "host.hpp")
      string(APPEND violations "${where}: a transport includes the host's class: ${line}\n")
    elseif(dir STREQUAL "net" AND target_dir STREQUAL "net")
      transport_of("${target_name}" theirs)
      if(mine AND theirs AND NOT mine STREQUAL theirs)
        string(APPEND violations "${where}: the ${mine} transport includes the ${theirs} transport's: ${line}\n")
      endif()
    endif()
  endforeach()
endforeach()

if(violations)
  message(FATAL_ERROR "transports meet only through server/host/transport.hpp:\n${violations}")
endif()
message(STATUS "check_transports: each transport includes only its own files and the host's interface")
