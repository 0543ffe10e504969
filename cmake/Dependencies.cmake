# Every dependency comes from a Debian package (scripts/setup.sh installs them).
find_package(Threads REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(GMPXX REQUIRED IMPORTED_TARGET gmpxx gmp)
find_package(LibLZMA REQUIRED)
find_package(ZLIB REQUIRED)  # compressed .vtu
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
# CGAL: the validator's convex hull (engine/src/exact_volume.cpp), the oracle tests, the bench.
find_package(CGAL REQUIRED)
if(DTLAB_BUILD_TESTS)
  find_package(GTest REQUIRED)
  find_package(rapidcheck REQUIRED)
endif()
if(DTLAB_BUILD_BENCH)
  find_package(benchmark REQUIRED)
endif()

# The Python binding (python/): pybind11 and numpy for Debian's python3, found as the first
# python3 on PATH unless Python3_EXECUTABLE says otherwise; a pyenv or venv python3 without numpy
# would build a module nobody can import, so /usr/bin/python3 is preferred where it exists.
if(DTLAB_BUILD_PYTHON)
  if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 REQUIRED COMPONENTS Interpreter Development.Module)
  find_package(pybind11 CONFIG REQUIRED)
endif()
