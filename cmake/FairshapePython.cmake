# Whether the Python module can be built: FAIRSHAPE_WITH_PYTHON defaults to ON when pybind11
# (Debian: pybind11-dev) and Python's headers are found; missing, the build goes on without it
# and says so. Sets FAIRSHAPE_PYTHON (build it) and FAIRSHAPE_PYTHON_INSTALL_DIR.
#
# Debian's /usr/bin/python3 is preferred to whatever `python3` comes first on PATH (a pyenv or
# venv interpreter lacks the Debian packages python3-numpy, -scipy, -pandas the module and its
# tests use); -DPython3_EXECUTABLE=... chooses another.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter of the fairshape module")
endif()
find_package(Python3 3.9 QUIET COMPONENTS Interpreter Development.Module)
if(Python3_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)
endif()
if(Python3_FOUND AND pybind11_FOUND)
  set(fairshape_python_default ON)
else()
  set(fairshape_python_default OFF)
endif()
option(FAIRSHAPE_WITH_PYTHON "Python bindings (module fairshape; needs pybind11 and the Python headers)"
       ${fairshape_python_default})

set(FAIRSHAPE_PYTHON OFF)
if(FAIRSHAPE_WITH_PYTHON)
  if(NOT Python3_FOUND)
    message(WARNING "fairshape: FAIRSHAPE_WITH_PYTHON is ON but no Python 3 interpreter with headers was found "
                    "(Debian: python3-dev): the Python module is not built")
  elseif(NOT pybind11_FOUND)
    message(WARNING "fairshape: FAIRSHAPE_WITH_PYTHON is ON but pybind11 was not found (Debian: pybind11-dev): "
                    "the Python module is not built")
  elseif(NOT (FAIRSHAPE_WITH_VTK AND FAIRSHAPE_WITH_CGAL AND FAIRSHAPE_WITH_CERES AND FAIRSHAPE_WITH_TBB))
    # fairshape.run and the registries come from the experiment library, which needs all four.
    message(STATUS "fairshape: the Python module needs VTK, CGAL, Ceres and TBB (the experiment library): not built")
  else()
    set(FAIRSHAPE_PYTHON ON)
  endif()
else()
  if(fairshape_python_default)
    message(STATUS "fairshape: Python module off (FAIRSHAPE_WITH_PYTHON=OFF)")
  else()
    message(STATUS "fairshape: Python module not built: pybind11 (Debian: pybind11-dev) or the Python 3 headers "
                   "(python3-dev) were not found")
  endif()
endif()

# Where `cmake --install` puts the package, relative to the prefix. Debian's python3 reads
# <prefix>/lib/python3.X/dist-packages for the prefix /usr/local (make install's default), so
# that is the folder where the interpreter is Debian's; elsewhere the interpreter's own
# posix_prefix scheme (lib/python3.X/site-packages).
if(FAIRSHAPE_PYTHON)
  execute_process(COMMAND ${Python3_EXECUTABLE} -c
    "import sysconfig; print(sysconfig.get_path('platlib', 'posix_prefix', vars={'platbase': '@P@', 'base': '@P@'}).replace('@P@/', '', 1))"
    OUTPUT_VARIABLE fairshape_python_platlib OUTPUT_STRIP_TRAILING_WHITESPACE)
  if("${Python3_SITEARCH}" MATCHES "dist-packages")
    set(fairshape_python_platlib lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/dist-packages)
  elseif(NOT fairshape_python_platlib OR IS_ABSOLUTE "${fairshape_python_platlib}")
    set(fairshape_python_platlib lib/python${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}/site-packages)
  endif()
  set(FAIRSHAPE_PYTHON_INSTALL_DIR ${fairshape_python_platlib} CACHE STRING
      "install folder of the Python package, relative to the prefix")
  message(STATUS "fairshape: Python module for ${Python3_EXECUTABLE} (${Python3_VERSION}), pybind11 ${pybind11_VERSION}, "
                 "installed into <prefix>/${FAIRSHAPE_PYTHON_INSTALL_DIR}")
endif()
