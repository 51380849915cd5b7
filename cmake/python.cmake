# The Python module (python/): on by default when an interpreter, its headers and pybind11 are found.
# The interpreter is chosen before anything else looks for one, so the module, its tests and the other
# Python tests agree. Without -DPython3_EXECUTABLE, the first of `python3` on PATH and /usr/bin/python3
# that imports numpy and pytest is taken: scripts/deps.sh installs those for Debian's interpreter, and a
# python3 earlier on PATH (pyenv, a virtual environment without them) would build a module it cannot test.
if(NOT DEFINED Python3_EXECUTABLE)
  find_program(SM_PATH_PYTHON3 python3)
  foreach(candidate ${SM_PATH_PYTHON3} /usr/bin/python3)
    if(EXISTS ${candidate})
      execute_process(COMMAND ${candidate} -c "import numpy, pytest" RESULT_VARIABLE rc
        OUTPUT_QUIET ERROR_QUIET)
      if(rc EQUAL 0)
        set(Python3_EXECUTABLE ${candidate} CACHE FILEPATH "The Python interpreter (module, tests)")
        break()
      endif()
    endif()
  endforeach()
endif()

find_package(Python3 COMPONENTS Interpreter Development.Module)
set(sm_python_default OFF)
# Not in the sanitizer builds: the interpreter that loads the module is not instrumented.
if(Python3_FOUND AND NOT (SUPERMODAL_SANITIZE OR SUPERMODAL_FUZZ OR SUPERMODAL_TSAN))
  # pybind11's own search for Python is skipped: it reuses the interpreter found above.
  find_package(pybind11 2.10 CONFIG QUIET)
  if(pybind11_FOUND)
    set(sm_python_default ON)
  endif()
endif()
option(SUPERMODAL_PYTHON "Build the Python module supermodal (pybind11; python/)" ${sm_python_default})
if(SUPERMODAL_PYTHON AND NOT (Python3_FOUND AND pybind11_FOUND))
  message(FATAL_ERROR "SUPERMODAL_PYTHON needs Python 3 with its headers (python3-dev) and pybind11 "
    "(pybind11-dev); found Python: ${Python3_FOUND}, pybind11: ${pybind11_FOUND}")
endif()
if(SUPERMODAL_PYTHON)
  message(STATUS "Python module: ${Python3_EXECUTABLE} (${Python3_VERSION}), pybind11 ${pybind11_VERSION}")
else()
  message(STATUS "Python module off (SUPERMODAL_PYTHON; needs python3-dev and pybind11-dev)")
endif()
