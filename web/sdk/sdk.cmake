# The browser SDK in the native build (included by CMakeLists.txt here).
#
# 1. The client core for WebAssembly: this project configured again with Debian's emscripten
#    toolchain in build/web-sdk/wasm (-O2; only arena-sdk-core and what it links are built).
#    ccache cannot cache em++, so this is the slow step (about two minutes of CPU from scratch).
# 2. npm ci from web/sdk/package-lock.json into build/web-sdk (esbuild, typescript, flatbuffers).
# 3. flatc --ts from protocol/arena.fbs into build/web-sdk/gen (generated, never committed).
# 4. tsc checks the types; esbuild bundles src/index.ts into build/web-sdk/dist/arena-sdk.mjs,
#    beside arena_core.mjs and arena_core.wasm.
# 5. The tests (web/sdk/test/*.test.mjs) run under `node --test` from ctest.
find_program(ARENA_NODE node REQUIRED)
find_program(ARENA_NPM npm REQUIRED)
find_program(ARENA_EMXX em++ REQUIRED)
set(ARENA_EMSCRIPTEN_TOOLCHAIN /usr/share/emscripten/cmake/Modules/Platform/Emscripten.cmake
    CACHE FILEPATH "emscripten's CMake toolchain file (Debian's emscripten package)")
if(NOT EXISTS ${ARENA_EMSCRIPTEN_TOOLCHAIN})
  message(FATAL_ERROR "${ARENA_EMSCRIPTEN_TOOLCHAIN} not found: install emscripten (make deps) "
                      "or configure with -DARENA_BUILD_SDK=OFF")
endif()

set(sdk_dir ${CMAKE_BINARY_DIR}/web-sdk)
set(wasm_dir ${sdk_dir}/wasm)
set(dist_dir ${sdk_dir}/dist)
# Debian's em++ finds its JavaScript modules (acorn) only through NODE_PATH.
set(em_env ${CMAKE_COMMAND} -E env NODE_PATH=/usr/share/nodejs)

# 1. WebAssembly. The nested build is configured once; its ninja then decides what to rebuild,
# so the target runs every time (a no-op costs well under a second).
add_custom_command(
  OUTPUT ${wasm_dir}/build.ninja
  COMMAND ${em_env} ${CMAKE_COMMAND} -S ${PROJECT_SOURCE_DIR} -B ${wasm_dir} -G Ninja
          -DCMAKE_TOOLCHAIN_FILE=${ARENA_EMSCRIPTEN_TOOLCHAIN}
          # Eigen's CMake config is on the host; its target names only /usr/include/eigen3.
          -DCMAKE_FIND_ROOT_PATH_MODE_PACKAGE=BOTH
          -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG"
          -DARENA_WITH_NET=OFF -DARENA_BUILD_TESTS=OFF -DARENA_BUILD_BENCH=OFF -DARENA_BUILD_SDK=OFF
          -DARENA_WERROR=${ARENA_WERROR}
  COMMENT "Configuring the WebAssembly build of the client core"
  VERBATIM)
add_custom_target(arena_sdk_wasm ALL
  COMMAND ${em_env} ${CMAKE_COMMAND} --build ${wasm_dir} --target arena-sdk-core
  COMMAND ${CMAKE_COMMAND} -E make_directory ${dist_dir}
  COMMAND ${CMAKE_COMMAND} -E copy_if_different ${wasm_dir}/bin/arena_core.mjs ${wasm_dir}/bin/arena_core.wasm
          ${dist_dir}
  DEPENDS ${wasm_dir}/build.ninja
  BYPRODUCTS ${dist_dir}/arena_core.mjs ${dist_dir}/arena_core.wasm
  COMMENT "Building the client core for WebAssembly (em++ -O2)"
  USES_TERMINAL
  VERBATIM)

# 2. npm packages, from the lock file only.
add_custom_command(
  OUTPUT ${sdk_dir}/node_modules/.package-lock.json
  COMMAND ${CMAKE_COMMAND} -E make_directory ${sdk_dir}
  COMMAND ${CMAKE_COMMAND} -E copy ${CMAKE_CURRENT_SOURCE_DIR}/package.json
          ${CMAKE_CURRENT_SOURCE_DIR}/package-lock.json ${sdk_dir}
  COMMAND ${ARENA_NPM} ci --prefix ${sdk_dir} --no-audit --no-fund --silent
  DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/package.json ${CMAKE_CURRENT_SOURCE_DIR}/package-lock.json
  COMMENT "npm ci (web/sdk/package-lock.json)"
  VERBATIM)

# 3. The schema's TypeScript.
add_custom_command(
  OUTPUT ${sdk_dir}/gen/arena_generated.ts
  COMMAND ${CMAKE_COMMAND} -E rm -rf ${sdk_dir}/gen
  COMMAND flatbuffers::flatc --ts -o ${sdk_dir}/gen ${PROJECT_SOURCE_DIR}/protocol/arena.fbs
  DEPENDS ${PROJECT_SOURCE_DIR}/protocol/arena.fbs flatbuffers::flatc
  COMMENT "flatc --ts protocol/arena.fbs"
  VERBATIM)

# 4. Type check (and declarations into dist/types), then bundle. The tsconfig is made here: its
# paths name the generated code and node_modules in the build directory. The bundle imports
# the core's loader (./arena_core.mjs) at run time, from beside itself.
set(SDK_SOURCE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
configure_file(tsconfig.json.in ${sdk_dir}/tsconfig.json @ONLY)
file(GLOB sdk_sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.ts)
add_custom_command(
  OUTPUT ${dist_dir}/arena-sdk.mjs
  COMMAND ${ARENA_NODE} ${sdk_dir}/node_modules/typescript/bin/tsc -p ${sdk_dir}/tsconfig.json
  COMMAND ${sdk_dir}/node_modules/.bin/esbuild ${CMAKE_CURRENT_SOURCE_DIR}/src/index.ts --bundle --format=esm
          --platform=neutral --main-fields=module,main --target=es2020 --tsconfig=${sdk_dir}/tsconfig.json
          --external:./arena_core.mjs --log-level=warning
          --outfile=${dist_dir}/arena-sdk.mjs
  DEPENDS ${sdk_sources} ${sdk_dir}/tsconfig.json ${sdk_dir}/gen/arena_generated.ts
          ${sdk_dir}/node_modules/.package-lock.json
  WORKING_DIRECTORY ${sdk_dir}
  COMMENT "tsc and esbuild: build/web-sdk/dist/arena-sdk.mjs"
  VERBATIM)
add_custom_target(arena_sdk_ts ALL DEPENDS ${dist_dir}/arena-sdk.mjs)
add_dependencies(arena_sdk_ts arena_sdk_wasm)

# A real match's session, recorded from the native build for the tests to replay in wasm.
add_executable(arena-sdk-record-session fixtures/record_session.cpp)
target_link_libraries(arena-sdk-record-session PRIVATE arena_match arena_client_core arena_config)
set(session_fixture ${sdk_dir}/fixtures/session.json)
add_custom_command(
  OUTPUT ${session_fixture}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${sdk_dir}/fixtures
  COMMAND arena-sdk-record-session ${session_fixture} 600
  DEPENDS arena-sdk-record-session
  COMMENT "Recording a match session for the SDK tests"
  VERBATIM)
# A short soccer match recorded as arena-server records one, for the replay player's game tests
# (its manifest, scoreboard with names, teams, events and result; web/page's replay test too).
add_executable(arena-sdk-record-soccer fixtures/record_soccer.cpp)
target_link_libraries(arena-sdk-record-soccer PRIVATE arena_replay arena_config arena_games)
set(soccer_fixture ${sdk_dir}/fixtures/soccer.arpl)
add_custom_command(
  OUTPUT ${soccer_fixture}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${sdk_dir}/fixtures
  COMMAND arena-sdk-record-soccer ${soccer_fixture}
  DEPENDS arena-sdk-record-soccer
  COMMENT "Recording a soccer match for the replay player's tests"
  VERBATIM)
add_custom_target(arena_sdk_fixtures ALL DEPENDS ${session_fixture} ${soccer_fixture})

# 5. The tests. The names start with "sdk" (ctest -R sdk).
file(GLOB sdk_tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test/*.test.mjs)
if(ARENA_BUILD_TESTS)
  foreach(test_file ${sdk_tests})
    get_filename_component(test_name ${test_file} NAME_WE)
    add_test(NAME sdk_${test_name} COMMAND ${ARENA_NODE} --test --test-reporter=spec ${test_file})
    set_tests_properties(sdk_${test_name} PROPERTIES
      ENVIRONMENT "ARENA_SDK_DIST=${dist_dir};ARENA_SDK_FIXTURES=${sdk_dir}/fixtures;ARENA_REPLAY=$<TARGET_FILE:arena-replay>;ARENA_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
      TIMEOUT 120)
  endforeach()
endif()
