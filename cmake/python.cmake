# The Python module `dynosize` (python/: the pybind11 binding _dynosize and the package around
# it), built when DYNOSIZE_PYTHON is ON and pybind11 and numpy are found for Debian's
# interpreter. Sets DYNOSIZE_PYTHON_FOUND.
#
# The interpreter: Debian's /usr/bin/python3 first (it has python3-pybind11 and python3-numpy,
# scripts/setup-debian.sh), not a python3 that happens to be first on PATH (a pyenv one has
# neither). -DPython3_EXECUTABLE=... chooses another.
set(DYNOSIZE_PYTHON_FOUND OFF)
if(NOT DYNOSIZE_PYTHON)
  return()
endif()
if(DYNOSIZE_SANITIZE OR DYNOSIZE_FUZZ)
  # An ASan-instrumented extension cannot be loaded by an interpreter built without ASan.
  message(STATUS "dynosize: Python module not built (not with DYNOSIZE_SANITIZE or DYNOSIZE_FUZZ)")
  return()
endif()
if(NOT Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 COMPONENTS Interpreter Development.Module NumPy)
if(Python3_FOUND AND Python3_Development.Module_FOUND)
  execute_process(COMMAND ${Python3_EXECUTABLE} -c "import pybind11; print(pybind11.get_cmake_dir())"
                  OUTPUT_VARIABLE DYNOSIZE_PYBIND11_DIR OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  find_package(pybind11 2.6 CONFIG QUIET HINTS ${DYNOSIZE_PYBIND11_DIR})
endif()
if(NOT pybind11_FOUND OR NOT Python3_NumPy_FOUND)
  message(STATUS "dynosize: Python module NOT built: pybind11 or numpy not found for "
                 "'${Python3_EXECUTABLE}' (install python3-pybind11 python3-numpy python3-dev, "
                 "scripts/setup-debian.sh; or -DDYNOSIZE_PYTHON=OFF to silence this)")
  return()
endif()
set(DYNOSIZE_PYTHON_FOUND ON)
message(STATUS "dynosize: Python module for ${Python3_EXECUTABLE} (Python ${Python3_VERSION}, pybind11 ${pybind11_VERSION})")

# The libraries go into a shared object: position-independent code. -fno-semantic-interposition
# keeps the calls inside the library direct (no symbol of it is replaced at load time), so that
# the CLI, linked against the same libraries, keeps its speed (docs/python.md).
foreach(_t dynosize_core dynosize_solvers dynosize_optimization)
  set_target_properties(${_t} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_compile_options(${_t} PRIVATE -fno-semantic-interposition)
endforeach()

file(GLOB DYNOSIZE_PYTHON_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/python/*.cc)
pybind11_add_module(_dynosize ${DYNOSIZE_PYTHON_SOURCES})
target_link_libraries(_dynosize PRIVATE dynosize_optimization)
target_compile_options(_dynosize PRIVATE ${DYNOSIZE_WARNINGS})
# build/python/dynosize/: the package with the compiled module beside it, importable from the
# build tree (PYTHONPATH=build/python; the ctest test python_module does so).
set_target_properties(_dynosize PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/python/dynosize)
configure_file(${PROJECT_SOURCE_DIR}/python/dynosize/__init__.py ${PROJECT_BINARY_DIR}/python/dynosize/__init__.py
               COPYONLY)

# Installed into <prefix>/lib/python3.X/dist-packages/dynosize: with the default prefix /usr/local
# (or /usr) a directory on Debian's python3 path; under another prefix P, PYTHONPATH=P/lib/python3.X/
# dist-packages. The package finds the catalog installed beside it (P/share/dynosize/catalog).
# DYNOSIZE_PYTHON_INSTALL_DIR chooses another place.
set(DYNOSIZE_PYTHON_INSTALL_DIR lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages
    CACHE STRING "where cmake --install puts the Python package dynosize (relative to the prefix)")
install(TARGETS _dynosize LIBRARY DESTINATION ${DYNOSIZE_PYTHON_INSTALL_DIR}/dynosize)
install(FILES ${PROJECT_SOURCE_DIR}/python/dynosize/__init__.py DESTINATION ${DYNOSIZE_PYTHON_INSTALL_DIR}/dynosize)
