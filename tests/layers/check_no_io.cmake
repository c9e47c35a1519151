# Fails when a source file under one of DIRS (';'-separated, relative to ROOT) includes Asio or
# Boost or reads a clock: the world and the match are pure functions of what they are handed,
# so that they replay bit for bit, run in virtual time, and build with clang++ for the fuzz
# targets.
#   cmake -DROOT=<source dir> -DDIRS="server/world;server/match" -P check_no_io.cmake
if(NOT ROOT OR NOT DIRS)
  message(FATAL_ERROR "check_no_io: pass -DROOT=... -DDIRS=...")
endif()

# One rule per line: a regular expression, then what it means.
set(rules
  "#[ \t]*include[ \t]*[<\"](boost|asio)[/.>]|includes Asio or Boost"
  "#[ \t]*include[ \t]*[<\"](chrono|ctime|time\\.h|sys/time\\.h)[>\"]|includes a clock header"
  "(steady_clock|system_clock|high_resolution_clock|utc_clock|file_clock)|reads a std::chrono clock"
  "(^|[^A-Za-z0-9_.>:])(time|clock|gettimeofday|clock_gettime|timespec_get)[ \t]*\\(|reads the time")

set(violations "")
foreach(dir IN LISTS DIRS)
  file(GLOB_RECURSE files "${ROOT}/${dir}/*.cpp" "${ROOT}/${dir}/*.hpp" "${ROOT}/${dir}/*.h")
  foreach(file IN LISTS files)
    # One list element per line: semicolons and brackets would split or join list elements.
    file(READ "${file}" text)
    string(REGEX REPLACE "[][;]" "_" text "${text}")
    string(REPLACE "\n" ";" lines "${text}")
    set(number 0)
    foreach(line IN LISTS lines)
      math(EXPR number "${number} + 1")
      string(REGEX REPLACE "//.*$" "" code "${line}")  # comments may name a clock
      foreach(rule IN LISTS rules)
        string(REPLACE "|" ";" parts "${rule}")
        list(POP_BACK parts what)
        list(JOIN parts "|" pattern)
        if(code MATCHES "${pattern}")
          file(RELATIVE_PATH where "${ROOT}" "${file}")
          string(APPEND violations "${where}:${number}: ${what}: ${line}\n")
        endif()
      endforeach()
    endforeach()
  endforeach()
endforeach()

if(violations)
  message(FATAL_ERROR "no sockets and no clock in ${DIRS}:\n${violations}")
endif()
message(STATUS "check_no_io: ${DIRS}: no Asio, Boost or clock")
