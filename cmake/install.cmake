# Installing Tandem (cmake --install BUILD --prefix P): the headers, libtandem, the `tandem` command
# and its scene files, and what lets other projects use it: lib/cmake/Tandem/TandemConfig.cmake
# (find_package(Tandem), the imported target Tandem::tandem) and lib/pkgconfig/tandem.pc.
include(CMakePackageConfigHelpers)

set(TANDEM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Tandem)
set(TANDEM_INSTALL_SCENEDIR ${CMAKE_INSTALL_DATADIR}/tandem/scenes)

install(DIRECTORY include/tandem DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/include/tandem/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tandem)
install(TARGETS tandem EXPORT TandemTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})

# The command, and the scene files `tandem list` shows (found relative to the installed command,
# so the installed tree can be moved).
install(TARGETS tandem_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY scenes/ DESTINATION ${TANDEM_INSTALL_SCENEDIR})
file(RELATIVE_PATH _scenes_from_bin /prefix/${CMAKE_INSTALL_BINDIR} /prefix/${TANDEM_INSTALL_SCENEDIR})
target_compile_definitions(tandem_cli PRIVATE TANDEM_INSTALLED_SCENE_DIR="${_scenes_from_bin}")
if(BUILD_SHARED_LIBS)
  file(RELATIVE_PATH _lib_from_bin /prefix/${CMAKE_INSTALL_BINDIR} /prefix/${CMAKE_INSTALL_LIBDIR})
  set_target_properties(tandem_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${_lib_from_bin}")
endif()

# find_package(Tandem): the targets, a config that finds what they need, and the version (before
# 1.0, a minor version is a new ABI: SameMinorVersion, as the SONAME).
install(EXPORT TandemTargets NAMESPACE Tandem:: DESTINATION ${TANDEM_INSTALL_CMAKEDIR})
if(BUILD_SHARED_LIBS)
  set(TANDEM_SHARED_LIBRARY ON)
  set(TANDEM_LIBRARY_KIND shared)
else()
  set(TANDEM_SHARED_LIBRARY OFF)
  set(TANDEM_LIBRARY_KIND static)
endif()
configure_package_config_file(cmake/TandemConfig.cmake.in ${PROJECT_BINARY_DIR}/TandemConfig.cmake
                              INSTALL_DESTINATION ${TANDEM_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/TandemConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/TandemConfig.cmake ${PROJECT_BINARY_DIR}/TandemConfigVersion.cmake
        DESTINATION ${TANDEM_INSTALL_CMAKEDIR})

# pkg-config. Paths are relative to the .pc file, so the installed tree can be moved. A static
# libtandem has no record of what it links, so its users link Bullet and tinyobjloader themselves:
# they are in Requires (plain `pkg-config --libs tandem` works); a shared libtandem names them
# itself, so they are only needed for --static.
set(TANDEM_PC_REQUIRES "eigen3 >= 3.4")
set(TANDEM_PC_PRIVATE_DEPENDENCIES "bullet-float64 tinyobjloader")
if(BUILD_SHARED_LIBS)
  set(TANDEM_PC_REQUIRES_PRIVATE ${TANDEM_PC_PRIVATE_DEPENDENCIES})
  set(TANDEM_PC_CFLAGS " -DTANDEM_SHARED")
else()
  string(APPEND TANDEM_PC_REQUIRES " ${TANDEM_PC_PRIVATE_DEPENDENCIES}")
  set(TANDEM_PC_REQUIRES_PRIVATE "")
  set(TANDEM_PC_CFLAGS "")
endif()
set(_pkgconfig_dir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
foreach(dir IN ITEMS LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    set(TANDEM_PC_${dir} "${CMAKE_INSTALL_${dir}}")
  else()
    set(TANDEM_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(TANDEM_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH _prefix_from_pc /prefix/${_pkgconfig_dir} /prefix)
  string(REGEX REPLACE "/$" "" _prefix_from_pc "${_prefix_from_pc}")
  set(TANDEM_PC_PREFIX "\${pcfiledir}/${_prefix_from_pc}")
endif()
configure_file(cmake/tandem.pc.in ${PROJECT_BINARY_DIR}/tandem.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/tandem.pc DESTINATION ${_pkgconfig_dir})
