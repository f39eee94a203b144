# pip builds the package from the source tree (setup.py drives CMake) and installs it into a
# temporary target; `import tandem` then works from there alone, steps a world and reads a view.
# Usage: cmake -DPYTHON=... -DSOURCE_DIR=... -DBUILD_DIR=... -DWORK_DIR=... -P pip_install.cmake
#
# pip compiles the library and the module again, from the same sources with the same flags as
# the build tree BUILD_DIR (WORK_DIR is under it). With ccache, and base_dir set to BUILD_DIR as
# scripts/setup.sh sets it for that build, each compiler call is the build tree's own (the
# generated include/ folder is `include` relative to either build's folder), so pip gets those
# objects from the cache: its build then costs a configure and links, not 7 CPU-minutes. What
# ccache found is printed (ccache --print-stats: hits, misses).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
find_program(CCACHE ccache)
set(cmake_args "")
set(ccache_env "")
if(CCACHE)
  set(cmake_args "-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache")
  set(ccache_env "CCACHE_BASEDIR=${BUILD_DIR}" "CCACHE_DEPEND=1")
  execute_process(COMMAND ${CCACHE} --print-stats OUTPUT_VARIABLE stats_before)
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env "CMAKE_ARGS=${cmake_args}" "TANDEM_PIP_BUILD_DIR=${WORK_DIR}/setuptools"
          ${ccache_env} ${PYTHON} -m pip install --no-build-isolation --no-deps --no-index --disable-pip-version-check
          --target "${WORK_DIR}/site" "${SOURCE_DIR}"
  RESULT_VARIABLE failed)
if(CCACHE)
  execute_process(COMMAND ${CCACHE} --print-stats OUTPUT_VARIABLE stats_after)
  foreach(counter IN ITEMS direct_cache_hit preprocessed_cache_hit cache_miss)
    string(REGEX MATCH "(^|\n)${counter}\t([0-9]+)" _ "${stats_before}")
    set(before "${CMAKE_MATCH_2}")
    string(REGEX MATCH "(^|\n)${counter}\t([0-9]+)" _ "${stats_after}")
    math(EXPR count "${CMAKE_MATCH_2} - 0${before}")
    string(APPEND summary " ${counter} ${count}")
  endforeach()
  message(STATUS "ccache during pip install (other builds at the same time count too):${summary}")
endif()
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
