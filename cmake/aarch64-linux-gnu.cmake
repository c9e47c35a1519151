# Cross build for 64-bit ARM Linux with Debian's g++-aarch64-linux-gnu, linked statically so
# that qemu-aarch64-static runs the programs without an ARM root file system. Used by
# scripts/determinism-check.sh for arena-replay only (ARENA_WITH_NET=OFF, no tests, no
# benchmarks):
#
#   cmake -S . -B build-aarch64 -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
#     -DARENA_WITH_NET=OFF -DARENA_BUILD_TESTS=OFF -DARENA_BUILD_BENCH=OFF
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_EXE_LINKER_FLAGS_INIT -static)

# Libraries and headers come from the ARM sysroot only; programs that run during the build
# (flatc) from the host. Packages are searched on the host too: Eigen's config only names a
# header directory. The header-only libraries whose Debian config targets would put the host's
# /usr/include on the compile line are replaced in cmake/third_party.cmake.
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE BOTH)

# Lets CMake (and `ctest`, if tests were built) run the ARM programs on this machine.
find_program(ARENA_QEMU_AARCH64 qemu-aarch64-static)
if(ARENA_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${ARENA_QEMU_AARCH64})
endif()
