# pip builds the package from the source tree (setup.py drives CMake) and installs it into a
# temporary target; `import tandem` then works from there alone, steps a world and reads a view.
# Usage: cmake -DPYTHON=... -DSOURCE_DIR=... -DWORK_DIR=... -P pip_install.cmake
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
find_program(CCACHE ccache)
set(cmake_args "")
if(CCACHE)
  set(cmake_args "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache")
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env "CMAKE_ARGS=${cmake_args}" "TANDEM_PIP_BUILD_DIR=${WORK_DIR}/setuptools"
          ${PYTHON} -m pip install --no-build-isolation --no-deps --no-index --disable-pip-version-check
          --target "${WORK_DIR}/site" "${SOURCE_DIR}"
  RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "pip install failed (${failed})")
endif()
# Run from an empty folder with only the target on the path: the installed package is the one imported.
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env "PYTHONPATH=${WORK_DIR}/site"
          ${PYTHON} -c "import tandem, sys; assert tandem.__file__.startswith(sys.argv[1]), tandem.__file__; \
w = tandem.World(); r = w.add_deformable(tandem.DeformableDesc(name='r', mesh=tandem.make_rope((0,1,0),(1,1,0),5,0.1))); \
p = w.node_positions(r); w.step(0.01); assert abs(p[0,1] - (1 - 9.81e-4)) < 1e-12, p[0,1]; \
print('pip-installed tandem', tandem.__version__, 'from', tandem.__file__)" "${WORK_DIR}/site/tandem"
  WORKING_DIRECTORY "${WORK_DIR}"
  RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "import tandem from the pip target failed (${failed})")
endif()
