# `cmake --install` of the python component into a temporary prefix puts the package in the
# interpreter's platlib under that prefix, and it imports from there.
# Usage: cmake -DPYTHON=... -DBUILD_DIR=... -DPREFIX=... -DPLATLIB=... -P cmake_install.cmake
file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${PREFIX}" --component python
                RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "cmake --install failed (${failed})")
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env "PYTHONPATH=${PREFIX}/${PLATLIB}"
          ${PYTHON} -c "import tandem, sys; assert tandem.__file__.startswith(sys.argv[1]), tandem.__file__; \
tandem.make_rope((0,0,0),(1,0,0),3,1.0); print('installed tandem', tandem.__version__, 'in', tandem.__file__)" "${PREFIX}/${PLATLIB}/tandem"
  WORKING_DIRECTORY "${PREFIX}"
  RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "import tandem from ${PREFIX}/${PLATLIB} failed (${failed})")
endif()
